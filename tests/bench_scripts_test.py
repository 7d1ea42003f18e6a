#!/usr/bin/env python3
"""bench/: the sections bench/regenerate.py --check finds and their revisions, the marker
generated_line writes, the stale check against this clone's history, and the targets table
bench/targets.py derives from the other sections."""
import json
import subprocess
import sys
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))

import readme_section  # noqa: E402
import regenerate  # noqa: E402
import targets  # noqa: E402


class Sections(unittest.TestCase):
    def test_each_section_takes_its_own_marker_and_reports_share_the_title_one(self):
        line = readme_section.generated_line("bench/x.py --readme", rev="abc1234")
        self.assertIn("`bench/x.py --readme` at revision abc1234", line)
        text = "\n".join([
            "# Speed against error", "", readme_section.generated_line("bench/report.py",
                                                                       rev="1111111"),
            "## Error against time (path tracing)", "text",
            "## Hit accuracy against speed", "text",
            "## EDACRT against DACRT (the paper's experiment)",
            readme_section.generated_line("p", rev="2222222+changes"),
            "## Why the defaults", readme_section.generated_line("hand", rev="3333333"),
            "## BVH baseline", "an old section without a marker",
        ])
        found = regenerate.section_revisions(text)
        self.assertEqual(found["## Error against time (path tracing)"], "1111111")
        self.assertEqual(found["## Hit accuracy against speed"], "1111111")
        self.assertEqual(found["## EDACRT against DACRT (the paper's experiment)"],
                         "2222222+changes")
        self.assertIsNone(found["## BVH baseline"])  # the marker above is another section's
        self.assertNotIn("## Why the defaults", found)  # not a generator's section
        self.assertNotIn("## Dynamic scenes", found)  # absent

    def test_the_check_names_stale_and_unmarked_sections_and_never_fails(self):
        head = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT,
                              capture_output=True, text=True).stdout.strip()
        if not head:
            self.skipTest("not a git checkout")
        first = subprocess.run(["git", "rev-list", "--max-parents=0", "HEAD"], cwd=ROOT,
                               capture_output=True, text=True).stdout.split()[0][:7]
        readme = ROOT / "out" / "bench_scripts_test" / "README.md"
        readme.parent.mkdir(parents=True, exist_ok=True)
        readme.write_text("\n".join([
            "## BVH baseline", readme_section.generated_line("b", rev=head),
            "## Dynamic scenes", readme_section.generated_line("d", rev=first),
            "## Deviations from the paper, measured", "no marker",
            "## Each method at its best: the switch sweep",
            readme_section.generated_line("s", rev="0000000"), ""]))
        out = subprocess.run([sys.executable, "-c", "import regenerate, pathlib, sys; "
                              f"regenerate.README = pathlib.Path({str(readme)!r}); "
                              "regenerate.check()"],
                             cwd=ROOT / "bench", capture_output=True, text=True)
        self.assertEqual(out.returncode, 0, out.stderr)
        self.assertNotIn("BVH baseline", out.stdout)  # measured on HEAD
        self.assertRegex(out.stdout, r"Dynamic scenes: \d+ engine/ file\(s\) changed since")
        self.assertIn("Deviations from the paper, measured: names no revision", out.stdout)
        self.assertIn("revision 0000000 is not in this clone", out.stdout)


class Targets(unittest.TestCase):
    """targets.py against made-up sections whose verdicts are known."""

    def setUp(self):
        self.dir = ROOT / "out" / "bench_scripts_test" / "targets"
        (self.dir / "results").mkdir(parents=True, exist_ok=True)
        self.readme = self.dir / "README.md"

    def write(self, name, data):
        (self.dir / "results" / name).write_text(json.dumps(data))

    def bench_row(self, scene, set_, rays, ratio, scaling, bytes_):
        return {"method": "edacrt", "scene": scene, "set": set_, "threads": 2, "rays": rays,
                "frame_time_per_best_embree": ratio, "scaling_1_thread_over_n": scaling,
                "working_bytes": bytes_}

    def test_each_target_is_judged_from_its_section(self):
        marker = readme_section.generated_line
        per_ray, per_scene = 36, 5000  # bytes: the memory row must find 36 per ray
        rows = [self.bench_row(scene, set_, rays, ratio, scaling, per_ray * rays + per_scene)
                for scene, set_, rays, ratio, scaling in [
                    ("bunny", "camera-1spp", 4000, 0.9, 1.9), ("sponza", "camera-1spp", 4000,
                                                                1.1, 1.7),
                    ("bunny", "diffuse", 1000, 1.2, 1.9), ("sponza", "diffuse", 1000, 1.3, 1.9),
                    ("bunny", "ao", 1000, 1.4, 1.9), ("bunny", "shadow", 1000, 1.6, 1.9)]]
        rows.append(dict(rows[0], method="dacrt", frame_time_per_best_embree=9.0))  # not edacrt
        self.write("edacrt_bench_t.json", {"results": rows})
        self.write("render_bench_t.json", {"rows": [
            {"scene": "sponza", "method": "edacrt", "per_embree_median": 0.95},
            {"scene": "sponza", "method": "bvh", "per_embree_median": 3.0}]})
        frame = lambda method, ms: {"method": method, "scene": "bunny", "set": "sweep",  # noqa
                                    "rays": 100, "rays_per_triangle": 0.5,
                                    "frame_seconds_median": ms / 1e3}
        self.write("dynamic_explode_t.json", {"results": [
            frame("edacrt", 10), frame("bvh/refit", 20), frame("embree/dynamic", 5),
            dict(frame("edacrt", 1), rays_per_triangle=4.0)]})  # above 1 ray per triangle
        self.readme.write_text("\n".join([
            "## edacrt bench, measured", marker("b", rev="1111111"),
            "[x](results/edacrt_bench_t.json)",
            "## EDACRT against DACRT (the paper's experiment)", marker("p", rev="2222222"),
            "| scene | rays | count | DACRT ms | EDACRT ms | speed-up |",
            "| bunny | camera_16spp | 4 | 14 | 10 | **1.40** |",
            "### Counters", "| bunny | camera_16spp | edacrt | 35% | 0% | 0.0 |",
            "## Dynamic scenes", marker("d", rev="3333333"),
            "[x](results/dynamic_t.json) [y](results/dynamic_explode_t.json)",
            "## The render, against Embree", marker("r", rev="4444444"),
            "[x](results/render_bench_t.json)", ""]))
        saved = targets.README
        targets.README = self.readme
        try:
            sys.argv = ["targets.py", "--readme"]
            targets.main()
        finally:
            targets.README = saved
        lines = {line.split(" | ")[0].lstrip("| "): line for line in self.readme.read_text()
                 .splitlines() if line.startswith("| ")}

        def verdict(start):
            line = next(v for k, v in lines.items() if k.startswith(start))
            return line, line.split(" | ")[3]

        line, met = verdict("per frame, camera-1spp")
        self.assertIn("bunny 0.90, sponza 1.10", line)
        self.assertEqual(met, "**no**")
        self.assertEqual(verdict("per frame, diffuse")[1], "yes")  # 1.3 is within
        line, met = verdict("per frame, ao and shadow")
        self.assertIn("bunny shadow 1.60", line)
        self.assertEqual(met, "**no**")
        line, met = verdict("scaling")
        self.assertIn("below: sponza camera-1spp 1.70", line)
        self.assertEqual(met, "**no**")
        line, met = verdict("memory")
        self.assertIn("bunny 36.0", line)
        self.assertEqual(met, "yes")
        line, met = verdict("the render")
        self.assertIn("sponza 0.95", line)
        self.assertNotIn("3.00", line)
        self.assertEqual(met, "yes")
        line, met = verdict("16-spp camera rays")
        self.assertIn("bunny 1.40", line)  # the comparison's row, not the counters'
        self.assertEqual(met, "yes")
        line, met = verdict("dynamic, explode")
        self.assertIn("bunny vs bvh/refit 0.50, bunny vs embree/dynamic 2.00", line)
        self.assertEqual(met, "**no**")
        self.assertIn("[Dynamic scenes](#dynamic-scenes), 3333333", line)


if __name__ == "__main__":
    unittest.main()
