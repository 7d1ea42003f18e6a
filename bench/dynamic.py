#!/usr/bin/python3
"""Dynamic scenes: runs `edacrt bench --dynamic` (every method over the frames of an animation
on the bunny and Sponza, each frame's time split into the update of its structure and the
trace) for two animations: a wave (1, 4 and 16 spp and a sweep of 1/16 to 16 rays per triangle)
and an explosion, where a refitted tree degrades (1 spp and a sweep up to 1 ray per triangle:
issue 26's case). Keeps each JSON and markdown in bench/results/, draws bench/figures/
dynamic.png and dynamic_explode.png (per-frame time against rays per triangle, one line per
method) and, with --readme, puts the section into bench/README.md.

Run from the repository root after building edacrt, with nothing else heavy running:
  bench/dynamic.py --readme        (about 10 minutes on 2 cores)
  bench/dynamic.py --quick         (small sets, 2 frames: checks that it works)
  bench/dynamic.py --from bench/results/dynamic_DATE.json bench/results/dynamic_explode_DATE.json
                   --readme   (figures and section only)
Uses Debian's /usr/bin/python3 with python3-matplotlib (installed by scripts/setup).
"""
import argparse
import json
import os
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib import ticker  # noqa: E402

from bench_common import ROOT, SCENES_DIR, run as run_checked, scene_list  # noqa: E402
from readme_section import generated_line, revision, splice  # noqa: E402

HEADING = "## Dynamic scenes"
SWEEP = "0.0625,0.125,0.25,0.5,1,2,4,8,16"
# Each animation's sets: (--animate, --spp, --rays-per-triangle, the figure's name, the words
# that describe it). A refitted tree under the explosion traces many times slower, so its sets
# stop at 1 ray per triangle, the target's range.
ANIMATIONS = {
    "wave": ("wave", "1,4,16", SWEEP, "dynamic.png",
             "a travelling wave moving every vertex, so no part of a structure stays valid"),
    "explode": ("explode", "1", "0.0625,0.125,0.25,0.5,1", "dynamic_explode.png",
                "every triangle flies apart along its normal and back, so a refitted tree's "
                "boxes grow and overlap while a rebuilt one stays tight"),
}
STYLE = {  # method label: colour, line style
    "edacrt": ("tab:red", "-"),
    "edacrt/presplit-0": ("tab:red", ":"),
    "dacrt": ("tab:orange", "-"),
    "bvh/rebuild": ("tab:blue", "-"),
    "bvh/refit": ("tab:blue", "--"),
    "embree/rebuild": ("tab:green", "-"),
    "embree/dynamic": ("tab:green", "-."),
    "embree/refit": ("tab:green", "--"),
}


def command(args, animation, json_path, markdown_path):
    scenes = [flag for s in scene_list("bench_dynamic") for flag in ("--scene", s.name)]
    animate, spp, sweep = ANIMATIONS[animation][:3]
    if args.quick:
        spp, sweep = "1", "0.25,1"
    return ["nice", "-n", "0", args.build / "edacrt", "bench", "--dynamic", *scenes, "--scenes",
            args.scenes, "--animate", animate, "--width", args.size, "--height", args.size,
            "--spp", spp, "--rays-per-triangle", sweep, "--frames", args.frames, "--threads",
            args.threads, "--json", json_path, "--markdown", markdown_path]


def figure(results, path):
    scenes = list(dict.fromkeys(r["scene"] for r in results["results"]))
    fig, axes = plt.subplots(1, len(scenes), figsize=(6.2 * len(scenes), 4.6), squeeze=False)
    for ax, scene in zip(axes[0], scenes):
        rows = [r for r in results["results"] if r["scene"] == scene]
        triangles = rows[0]["triangles"]
        for method in dict.fromkeys(r["method"] for r in rows):
            sweep = sorted((r["rays_per_triangle"], 1e3 * r["frame_seconds_median"])
                           for r in rows if r["method"] == method and r["set"] == "sweep")
            colour, line = STYLE.get(method, ("black", "-"))
            ax.plot(*zip(*sweep), line, color=colour, marker=".", label=method)
            camera = [(r["rays_per_triangle"], 1e3 * r["frame_seconds_median"])
                      for r in rows if r["method"] == method and r["set"] != "sweep"]
            ax.plot(*zip(*camera), "o", color=colour, fillstyle="none", markersize=7)
        ax.set_xscale("log", base=2)
        ax.set_yscale("log")
        plain = ticker.FuncFormatter(lambda v, _: f"{v:g}")
        ax.xaxis.set_major_formatter(plain)
        ax.yaxis.set_major_formatter(plain)
        ax.yaxis.set_minor_formatter(ticker.FuncFormatter(
            lambda v, _: f"{v:g}" if f"{v:g}"[0] in "25" else ""))
        spp = "/".join(str(n) for n in results["settings"]["spp"])
        ax.set_xlabel(f"rays per triangle (camera rays, 1 spp; circles: the {spp}-spp sets)")
        ax.set_ylabel("per-frame time, update + trace (ms)")
        ax.set_title(f"{scene} ({triangles:,} triangles), {results['settings']['animation']}")
        ax.grid(True, which="both", alpha=0.3)
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def findings(results, animation):
    """Per scene: what EDACRT pays per frame without a structure, and what refits and rebuilds
    pay, from the sweep's smallest and largest sets."""
    lines = []
    for scene in dict.fromkeys(r["scene"] for r in results["results"]):
        sweep = [r for r in results["results"] if r["scene"] == scene and r["set"] == "sweep"]
        if not sweep:
            continue
        low = min(r["rays"] for r in sweep)
        high = max(r["rays"] for r in sweep)
        at = {(r["rays"], r["method"]): r for r in sweep}

        def ms(rays, method, key):
            row = at.get((rays, method))
            return f"{1e3 * row[key]:.1f}" if row else "n/a"

        def trace_ratio(method):
            a, b = at.get((high, method + "/refit")), at.get((high, method + "/rebuild"))
            return (f"{a['trace_seconds_median'] / b['trace_seconds_median']:.2f}x"
                    if a and b else "n/a")

        crossings = [f"{c['method']} from {c['text']}" for c in results["crossovers"]
                     if c["scene"] == scene]
        lines.append(
            f"* **{scene}**: at {low:,} rays ({low / sweep[0]['triangles']:.3g} per triangle) "
            f"EDACRT's frame is {ms(low, 'edacrt', 'frame_seconds_median')} ms: "
            f"{ms(low, 'edacrt', 'update_seconds_median')} ms of per-frame triangle data "
            f"({ms(low, 'edacrt/presplit-0', 'update_seconds_median')} ms without pre-split "
            f"pieces) and {ms(low, 'edacrt', 'trace_seconds_median')} ms of trace, much of it "
            "binning and partitioning triangles near the root of the recursion, whatever the "
            "number of rays (`edacrt trace --stats` gives the time per phase and level): the "
            "per-batch price of keeping no structure. Updates: bvh rebuild "
            f"{ms(low, 'bvh/rebuild', 'update_seconds_median')} ms, refit "
            f"{ms(low, 'bvh/refit', 'update_seconds_median')} ms; Embree rebuild "
            f"{ms(low, 'embree/rebuild', 'update_seconds_median')} ms, dynamic "
            f"{ms(low, 'embree/dynamic', 'update_seconds_median')} ms, refit "
            f"{ms(low, 'embree/refit', 'update_seconds_median')} ms. A refitted tree traces "
            f"{trace_ratio('bvh')} (bvh) and {trace_ratio('embree')} (Embree) as long as a "
            f"rebuilt one at {high:,} rays under this {animation}. Faster than EDACRT: "
            + "; ".join(crossings) + " rays per triangle.")
    return lines


def section(args, runs, elapsed):
    """runs: (animation, results, json_path, markdown text, load averages) per animation."""
    first = runs[0][1]
    s, machine = first["settings"], first["machine"]
    run = (f"bench/dynamic.py --readme --frames {args.frames} --size {args.size} "
           f"--threads {args.threads}")
    lines = [
        HEADING,
        "",
        generated_line(run, rev=first.get("revision", machine["git_revision"])),
        "",
        f"Run time: {elapsed}. {machine['cpu']}, {machine['hardware_threads']} hardware "
        f"threads, `--threads {s['threads']}`, {machine['date']}; the machine is shared, so "
        "read ratios within a set, not absolute times.",
        "",
        "Every method follows an animation frame by frame. Before the timed frames each tracer "
        "takes the frame at t = 0 (the structure a previous frame left); then each of "
        f"{s['frames']} frames, spread over one period, is timed as the update "
        "(`Tracer::update_scene()`: `bvh/rebuild` builds its binned-SAH BVH again, `bvh/refit` "
        "refits its boxes bottom-up with the same conservative triangle bounds; Embree "
        "(packet8) builds a new scene at medium quality, commits a dynamic scene at low quality, "
        "or refits with `RTC_BUILD_QUALITY_REFIT`; EDACRT and DACRT keep no structure and only "
        "gather the triangles, with EDACRT's default pre-split pieces (`--presplit`) or without) "
        "plus the trace of the same camera rays; methods interleaved with the first to go "
        "rotating, medians over the frames. The hits of every method are compared with EDACRT's "
        "on every frame. `x edacrt` is the frame time over EDACRT's. The crossover (each "
        "animation's last table) is where a method's frame time falls below EDACRT's for good, "
        "on a sweep of 1-spp camera sets (interpolated in log-log between the sweep's points); "
        "`below` the smallest: faster at every size measured; `above` the largest: slower at "
        "every size.",
        "",
    ]
    for animation, results, json_path, markdown_text, loads in runs:
        s = results["settings"]
        figure_name, words = ANIMATIONS[animation][3:]
        equivalent = " ".join(str(c) for c in command(args, animation, "OUT.json", "OUT.md")[4:])
        equivalent = equivalent.replace(f"--scenes {args.scenes} ", "")
        load_text = (f"1-minute load average {loads[0]:.1f} before and {loads[1]:.1f} after"
                     if loads else "load not recorded")
        lines += [
            f"### `{s['animation']}`",
            "",
            f"{words[0].upper() + words[1:]}. `build/edacrt {equivalent}`, kept in "
            f"[{json_path.name}](results/{json_path.name}) and "
            f"[{json_path.with_suffix('.md').name}](results/{json_path.with_suffix('.md').name})"
            f" ({load_text}); all methods agree: {'yes' if results['agreement_ok'] else 'NO'}. "
            f"Camera rays at {s['width']}x{s['height']} pixels:",
            "",
            markdown_text.split("\n\n", 1)[1].rstrip("\n"),
            "",
            f"![per-frame time against rays per triangle, {animation}](figures/{figure_name})",
            "",
            *findings(results, animation),
            "",
        ]
    return "\n".join(lines)


def measure(args, animation, out):
    suffix = "" if animation == "wave" else f"_{animation}"
    json_path = out / f"dynamic{suffix}_{time.strftime('%Y-%m-%d')}.json"
    before = os.getloadavg()[0]
    print(run_checked(command(args, animation, json_path, json_path.with_suffix(".md")),
                      tool="dynamic"), flush=True)
    results = json.loads(json_path.read_text())
    results["load_average"] = {"before": before, "after": os.getloadavg()[0]}
    results["revision"] = revision()
    json_path.write_text(json.dumps(results, indent=2) + "\n")
    return json_path


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--scenes", type=Path, default=SCENES_DIR)
    parser.add_argument("--size", type=int, default=512, help="image width and height")
    parser.add_argument("--frames", type=int, default=8, help="timed frames per set")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--from", dest="stored", type=Path, nargs="+",
                        help="stored JSONs (wave, then explode): redraw without running")
    parser.add_argument("--quick", action="store_true", help="small sets, 2 frames")
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    args = parser.parse_args()
    if args.quick:
        args.size, args.frames = 64, 2
    started = time.time()
    if args.stored:
        paths = args.stored
    else:
        if not (args.build / "edacrt").exists():
            sys.exit(f"dynamic: {args.build / 'edacrt'} not found; build it first")
        out = ROOT / ("out/bench" if args.quick else "bench/results")
        out.mkdir(parents=True, exist_ok=True)
        paths = [measure(args, animation, out) for animation in ANIMATIONS]
    elapsed = "redrawn from stored runs" if args.stored else f"{time.time() - started:.0f} s"
    figures = ROOT / ("out/bench" if args.quick else "bench/figures")
    figures.mkdir(parents=True, exist_ok=True)
    runs = []
    for json_path in paths:
        results = json.loads(json_path.read_text())
        animation = results["settings"]["animation"].split(":")[0]
        figure(results, figures / ANIMATIONS[animation][3])
        loads = ((results["load_average"]["before"], results["load_average"]["after"])
                 if "load_average" in results else None)
        runs.append((animation, results, json_path, json_path.with_suffix(".md").read_text(),
                     loads))
    text = section(args, runs, elapsed)
    if args.readme and not args.quick:
        splice(ROOT / "bench" / "README.md", HEADING, text)
    print(text)


if __name__ == "__main__":
    main()
