#!/usr/bin/env python3
"""bench/: the sections bench/regenerate.py --check finds and their revisions, the marker
generated_line writes, and the stale check against this clone's history."""
import subprocess
import sys
import unittest
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))

import readme_section  # noqa: E402
import regenerate  # noqa: E402


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


if __name__ == "__main__":
    unittest.main()
