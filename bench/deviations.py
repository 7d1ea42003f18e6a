#!/usr/bin/env python3
"""Where EDACRT's defaults deviate from the paper (Nabata et al. 2013), and what each deviation
buys: the default parameters against the same parameters with one choice put back to the
paper's, and the paper preset and DACRT for scale.

    /usr/bin/python3 bench/deviations.py [--runs 5] [--threads 2] [--readme] [--quick]

Ray sets: 1024x1024 pixel-centre camera rays (`edacrt camera-rays`) and 200,000 random rays
from inside the scene's box (uniform origins and directions), on the bunny and Sponza from
$EDACRT_SCENES (default ../shared/scenes). Every variant traces the same ray file with `edacrt
trace`; times are its trace_seconds (loading excluded), the variants interleaved run by run in
a rotating order, medians of --runs, run r with --sampling-seed 1 + r; box and triangle tests
are means over the runs, the other counters come from the first run's --stats.
"""
import argparse
import json
import re
import statistics
import subprocess
import sys
import time
from pathlib import Path

import numpy as np

from bench_common import ROOT, SCENES_DIR, scene_list
from readme_section import generated_line, splice

HEADING = "## Deviations from the paper, measured"


# (name, flags, what the flags put back to the paper's choice)
VARIANTS = [
    ("default", [], "our defaults"),
    ("small nodes: every ray", ["--small-nodes", "every-ray"],
     "nodes of <= 1000 rays sample every ray"),
    ("small nodes: surface area", ["--small-nodes", "surface-area"],
     "(not the paper) area ratios in nodes of <= 1000 rays"),
    ("small nodes: scaled", ["--small-nodes", "scaled"],
     "(not the paper) one ray in 16, at least one, in nodes of <= 1000 rays"),
    ("binning: centroids", ["--binning", "centroids"],
     "(not the paper) bins across the centroids' range"),
    ("cost leaf <= 64 tris", ["--cost-leaf-max-tris", "64"],
     "(not the paper) leaves by cost in small nodes"),
    ("filter skip: triangles", ["--filter-skip", "triangles"],
     "(not the paper) N C_child at any depth"),
    ("filter skip: off", ["--filter-skip", "off"], "always filter"),
    ("paper preset", ["--preset", "paper"], "all of the paper's choices"),
    ("dacrt", ["--preset", "dacrt"], "surface area, direction sign, always filter"),
]

SETS = [(s.name, s.relative) for s in scene_list("deviations")]  # under SCENES_DIR


def edacrt(build, *args):
    out = subprocess.run([str(build / "edacrt"), *map(str, args)], capture_output=True, text=True)
    if out.returncode != 0:
        sys.exit(f"edacrt {' '.join(map(str, args))} failed:\n{out.stderr}")
    return out.stdout + out.stderr


def scene_box(path):
    vertices = np.array([line.split()[1:4] for line in open(path) if line.startswith("v ")],
                        dtype=np.float64)
    return vertices.min(axis=0), vertices.max(axis=0)


def random_rays(path, lo, hi, count, seed=1):
    rng = np.random.default_rng(seed)
    org = lo + (hi - lo) * rng.random((count, 3))
    direction = rng.normal(size=(count, 3))
    direction /= np.linalg.norm(direction, axis=1)[:, None]
    rays = np.zeros((count, 8), dtype=np.float32)
    rays[:, 0:3], rays[:, 3:6], rays[:, 7] = org, direction, np.inf
    rays.tofile(path)


def measure(build, out, scene, rays, runs, threads):
    times = {name: [] for name, _, _ in VARIANTS}
    tests = {name: [] for name, _, _ in VARIANTS}  # (box, triangle) tests of each run
    counters = {}
    for run in range(runs):
        # Rotated every run, so that no variant always runs first (or right after another).
        for name, flags, _ in VARIANTS[run % len(VARIANTS):] + VARIANTS[:run % len(VARIANTS)]:
            stats = out / "stats.json"
            extra = ["--stats", stats] if run == 0 else []
            # A new draw of sampled rays every run: the tree depends on it.
            text = edacrt(build, "trace", "--scene", scene, "--rays", rays, "--out",
                          out / "hits.bin", "--threads", threads, "--sampling-seed", 1 + run,
                          *flags, *extra)
            match = re.search(r" in ([0-9.e+-]+) s:.* ([0-9]+) ray-box and ([0-9]+) ray-tri", text)
            times[name].append(float(match.group(1)))
            tests[name].append((int(match.group(2)), int(match.group(3))))
            if run == 0:
                s = json.loads(stats.read_text())
                levels = s["detail"]["levels"]
                n = s["rays"]
                counters[name] = {
                    "sampling": sum(l["sample_box_tests"] for l in levels) / n,
                    "skips": sum(l["filters_skipped"] for l in levels),
                }
    for name, t in tests.items():
        counters[name]["box"] = statistics.mean(b for b, _ in t) / n
        counters[name]["tri"] = statistics.mean(tri for _, tri in t) / n
    return {name: statistics.median(t) for name, t in times.items()}, counters


def markdown(results, args, seconds):
    lines = [
        HEADING,
        "",
        generated_line(args.command, seconds=seconds),
        "",
        "Each row puts one of our defaults back to the paper's choice (or, marked, to another "
        "option); *time* is relative to the defaults on the same ray set, medians of "
        f"{args.runs} interleaved runs of `edacrt trace` (the order rotated every run). Box "
        "tests include the sampling's. Run r draws sampled rays with `--sampling-seed 1+r`; box and "
        "triangle tests are means over the runs, sampling box tests and skips from the first.",
        "",
    ]
    for set_name, (medians, counters) in results.items():
        base = medians["default"]
        lines += [f"**{set_name}**", "",
                  "| variant | what changes | ms | time | box tests / ray (sampling) "
                  "| triangle tests / ray | filters skipped |",
                  "|---|---|---:|---:|---:|---:|---:|"]
        for name, _, what in VARIANTS:
            c = counters[name]
            lines.append(f"| {name} | {what} | {medians[name] * 1e3:.0f} | "
                         f"{medians[name] / base:.2f}x | {c['box']:.1f} ({c['sampling']:.1f}) | "
                         f"{c['tri']:.1f} | {c['skips']} |")
        lines.append("")
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "deviations")
    parser.add_argument("--runs", type=int, default=5)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--quick", action="store_true",
                        help="128x128 camera rays, 20,000 random ones, one run: a smoke test")
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    args = parser.parse_args()
    args.command = "bench/deviations.py " + " ".join(sys.argv[1:])
    if args.quick:
        args.runs, args.out = 1, args.out / "quick"
    args.out.mkdir(parents=True, exist_ok=True)
    started = time.time()
    results = {}
    for name, relative in SETS:
        scene = SCENES_DIR / relative
        if not scene.exists():
            print(f"skipping {name}: {scene} not found", file=sys.stderr)
            continue
        camera = args.out / f"{name}_camera.rays"
        size = ["--width", "128", "--height", "128"] if args.quick else []
        edacrt(args.build, "camera-rays", "--scene", scene, "--out", camera, *size)
        random = args.out / f"{name}_random.rays"
        random_rays(random, *scene_box(scene), 20_000 if args.quick else 200_000)
        sets = (("camera rays, 128x128", camera), ("random rays inside, 20k", random)) \
            if args.quick else (("camera rays, 1024x1024", camera),
                                ("random rays inside, 200k", random))
        for kind, rays in sets:
            print(f"{name}: {kind}", file=sys.stderr)
            results[f"{name}, {kind}"] = measure(args.build, args.out, scene, rays, args.runs,
                                                 args.threads)
    section = markdown(results, args, time.time() - started)
    print(section)
    if args.readme:
        splice(ROOT / "bench" / "README.md", HEADING, section)


if __name__ == "__main__":
    main()
