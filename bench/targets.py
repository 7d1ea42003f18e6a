#!/usr/bin/python3
"""Issue 26's speed targets against the figures the other generated sections of
bench/README.md measured: no run of its own. Reads the results each section links (the
per-frame bench, the render, the explosion of the dynamic scenes) and the paper experiment's
table, and writes one row per target: the goal, what was measured, met or not, and the
section (with its revision) it comes from. Run it after the others (bench/regenerate.py does).

  bench/targets.py --readme      (seconds)
"""
import argparse
import json
import math
import re
import sys
from pathlib import Path

from readme_section import MARKER, README, generated_line, sections, splice

HEADING = "## Issue 26's targets, measured"
LARGE = ["bunny", "sponza", "sibenik", "conference"]


class Missing(Exception):
    pass


class Source:
    """A generated section: its revision and the results files it links."""

    def __init__(self, lines, heading):
        self.heading = heading
        self.revision = next((m.group(1) for l in lines if (m := MARKER.search(l))), "?")
        self.links = re.findall(r"\]\(([^)]+\.json)\)", "\n".join(lines))
        self.lines = lines

    def json(self, pattern):
        """The linked results file whose name matches `pattern` (a link is relative to the
        README's folder, or absolute as smoke runs write them)."""
        link = next((n for n in self.links if re.fullmatch(pattern, Path(n).name)), None)
        path = README.parent / link if link else None
        if path is None or not path.is_file():
            raise Missing(f"{self.heading} links no {pattern} that exists")
        return json.loads(path.read_text())

    def cite(self):
        anchor = re.sub(r"[^a-z0-9 -]", "", self.heading[3:].lower()).replace(" ", "-")
        return f"[{self.heading[3:]}](#{anchor}), {self.revision}"


def ratios(values):
    return ", ".join(f"{k} {v:.2f}" for k, v in values.items())


def row(target, goal, measured, met, source):
    return f"| {target} | {goal} | {measured} | {'yes' if met else '**no**'} | {source} |"


def per_frame_rows(source):
    """Per frame, 2 threads, EDACRT over Embree's faster mode; and 1 -> 2 threads."""
    results = source.json(r"edacrt_bench_.*\.json")["results"]
    edacrt = [r for r in results if r["method"] == "edacrt"]
    threads = max(r["threads"] for r in edacrt)
    rows = []
    for sets, goal in ((["camera-1spp"], 1.0), (["diffuse"], 1.3), (["ao", "shadow"], 1.5)):
        got = {f"{r['scene']} {r['set']}" if len(sets) > 1 else r["scene"]:
               r["frame_time_per_best_embree"] for r in edacrt
               if r["threads"] == threads and r["set"] in sets and r["scene"] in LARGE}
        rows.append(row(f"per frame, {' and '.join(sets)} rays, {threads} threads: EDACRT / "
                        "Embree (its faster mode, build included)", f"<= {goal}",
                        ratios(got), all(v <= goal for v in got.values()), source.cite()))
    scaling = {f"{r['scene']} {r['set']}": r["scaling_1_thread_over_n"] for r in edacrt
               if r["threads"] == threads and r["scaling_1_thread_over_n"]}
    low = {k: v for k, v in scaling.items() if v < 1.8}
    rows.append(row(f"scaling, 1 -> {threads} threads, EDACRT, every set", ">= 1.8",
                    f"{min(scaling.values()):.2f}-{max(scaling.values()):.2f}; below: "
                    f"{ratios(low) or 'none'}", not low, source.cite()))
    # Working memory = bytes per ray x rays + a per-scene part (triangles): the per-ray part is
    # the slope between two sets of one scene with different ray counts.
    slopes = {}
    for scene in LARGE:
        sets = sorted({(r["rays"], r["working_bytes"]) for r in edacrt
                       if r["scene"] == scene and r["threads"] == threads})
        if len(sets) >= 2 and sets[-1][0] >= 2 * sets[0][0]:  # far enough apart to fit
            (r0, b0), (r1, b1) = sets[0], sets[-1]
            slopes[scene] = (b1 - b0) / (r1 - r0)
    if slopes:
        rows.append(row("memory: working bytes per ray (the slope between a scene's sets of "
                        "different ray counts; the rest is per triangle)", "<= 48",
                        ", ".join(f"{k} {v:.1f}" for k, v in slopes.items()),
                        all(v <= 48 for v in slopes.values()), source.cite()))
    return rows


def render_row(source):
    rows = source.json(r"render_bench_.*\.json")["rows"]
    got = {r["scene"]: r["per_embree_median"] for r in rows if r["method"] == "edacrt"}
    return row("the render (path tracing, 8 spp, 2 threads): EDACRT / Embree", "<= 1.0",
               ratios(got), all(v <= 1.0 for v in got.values()), source.cite())


def dacrt_row(source):
    """The paper experiment's 16-spp camera rows: speed-up, each at its best."""
    got = {}
    for line in source.lines:
        cells = [c.strip() for c in line.strip("|").split("|")]
        # The comparison table's rows (the counters' tables below it share the first cells).
        if len(cells) > 5 and cells[1] == "camera_16spp" and re.fullmatch(r"\*\*[0-9.]+\*\*",
                                                                             cells[5]):
            got[cells[0]] = float(cells[5].strip("*"))
    return row("16-spp camera rays: EDACRT / DACRT, each at its best (speed-up)", ">= 1.3",
               ratios(got), bool(got) and all(v >= 1.3 for v in got.values()), source.cite())


def dynamic_row(source):
    """Under the explosion, at <= 1 ray per triangle: EDACRT's frame over the refitted BVH's
    and Embree's dynamic scene's (the worst set of each scene)."""
    results = source.json(r"dynamic_explode_.*\.json")["results"]
    worst = {}
    for r in results:
        if r["method"] != "edacrt" or r["rays_per_triangle"] > 1.0 + 1e-9:
            continue
        for other in ("bvh/refit", "embree/dynamic"):
            match = next((o for o in results if o["method"] == other and o["scene"] == r["scene"]
                          and o["set"] == r["set"] and o["rays"] == r["rays"]), None)
            if match:
                key = f"{r['scene']} vs {other}"
                ratio = r["frame_seconds_median"] / match["frame_seconds_median"]
                worst[key] = max(worst.get(key, -math.inf), ratio)
    return row("dynamic, explode, <= 1 ray per triangle: EDACRT / other (the worst set)",
               "<= 1.0", ratios(worst), bool(worst) and all(v <= 1.0 for v in worst.values()),
               source.cite())


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    parser.add_argument("--quick", action="store_true",
                        help="a smoke run's README: leave out the rows whose results it lacks")
    args = parser.parse_args()
    found = sections(README.read_text())

    def source(heading):
        if heading not in found:
            sys.exit(f"targets: bench/README.md has no section {heading!r}; generate it first")
        return Source(found[heading], heading)

    rows = []
    for make, heading in ((per_frame_rows, "## edacrt bench, measured"),
                          (render_row, "## The render, against Embree"),
                          (dacrt_row, "## EDACRT against DACRT (the paper's experiment)"),
                          (dynamic_row, "## Dynamic scenes")):
        try:
            made = make(source(heading))
        except Missing as e:
            if not args.quick:
                sys.exit(f"targets: {e}")
            print(f"targets: {e} (a smoke run: the row is left out)", file=sys.stderr)
            continue
        rows += made if isinstance(made, list) else [made]
    text = "\n".join([
        HEADING, "",
        generated_line("bench/targets.py --readme"), "",
        "Issue 26's targets against the figures of the sections above (each named with the "
        "revision that measured it); this section measures nothing itself. Ratios below 1 are "
        "EDACRT faster, except the speed-up over DACRT.", "",
        "| target | goal | measured | met | from |", "|---|---|---|---|---|", *rows, ""])
    if args.readme:
        splice(README, HEADING, text)
    print(text)


if __name__ == "__main__":
    main()
