#!/usr/bin/python3
"""The render a user waits for: `edacrt render` (path tracing, the scene's default view) with
every method on Sponza, Sibenik and Conference, timed from the loaded scene to the finished
image (`prepare_seconds` + `render_seconds` of --stats: Embree's and the BVH's builds count,
loading the OBJ does not). Rounds run every method once each, in a shuffled order, so that the
machine's drift falls on all of them; a method's figure is its median over the rounds, and its
ratio to Embree the median of the per-round ratios.

  bench/render_bench.py --readme      (about 4 minutes on 2 cores)
  bench/render_bench.py --quick       (the Cornell box, 64x48, 2 spp, one round)
"""
import argparse
import functools
import json
import random
import statistics
import sys
import tempfile
import time
from pathlib import Path

from bench_common import ROOT, SCENES_DIR, run as run_checked, scene_list
from readme_section import generated_line, splice

HEADING = "## The render, against Embree"
METHODS = ["edacrt", "dacrt", "bvh", "embree"]
SCENES = ["sponza", "sibenik", "conference"]
run = functools.partial(run_checked, tool="render_bench")


def scene_paths(scenes_dir, names):
    known = {s.name: s for s in scene_list("bench")}
    return [(name, known[name].path(scenes_dir)) for name in names]


def render_once(build, scene, method, args, stats):
    run([build / "edacrt", "render", "--scene", scene, "--method", method, "--integrator",
         "path", "--width", args.width, "--height", args.height, "--spp", args.spp,
         "--threads", args.threads, "--seed", 1, "-q", "--stats", stats, "--out",
         stats.with_suffix(".pfm")])
    s = json.loads(stats.read_text())
    return {"seconds": s["prepare_seconds"] + s["render_seconds"],
            "trace_seconds": s["trace_seconds"], "batches": s["batches"], "rays": s["rays"],
            "passes": len(s["passes"]), "parts": parts(s)}


PARTS = ["prepare", "camera", "bounce:1", "bounce:2", "bounces 3+", "shadow rays",
         "shading and the rest"]


def part_of(batch):
    """The part of the render a batch kind's time goes to: the camera rays and the first two
    bounces (the whole image's paths) alone, the later bounces (after Russian roulette starts,
    smaller and smaller batches) together, and all shadow rays together."""
    kind, _, bounce = batch.partition(":")
    if kind == "bounce" and int(bounce) >= 3:
        return "bounces 3+"
    return "shadow rays" if kind == "shadow" else batch


def parts(stats):
    """Seconds and rays by part: the per-frame build (prepare), the batches (part_of) and the
    rest of the render (shading, sampling, the film)."""
    out = {"prepare": {"seconds": stats["prepare_seconds"], "rays": 0, "batches": 0}}
    for b in stats["batch_times"]:
        part = out.setdefault(part_of(b["batch"]), {"seconds": 0.0, "rays": 0, "batches": 0})
        for key in ("seconds", "rays", "batches"):
            part[key] += b[key]
    out["shading and the rest"] = {
        "seconds": stats["render_seconds"] - stats["trace_seconds"], "rays": 0, "batches": 0}
    return out


def measure(build, scenes, args):
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        stats = Path(tmp) / "stats.json"
        for name, path in scenes:
            runs = {m: [] for m in METHODS}
            order = list(METHODS)
            for r in range(args.rounds):
                random.Random(r).shuffle(order)
                for method in order:
                    runs[method].append(render_once(build, path, method, args, stats))
                print(f"render_bench: {name} round {r + 1}/{args.rounds}", file=sys.stderr,
                      flush=True)
            for method in METHODS:
                times = [x["seconds"] for x in runs[method]]
                ratios = [a["seconds"] / b["seconds"] for a, b in zip(runs[method], runs["embree"])]
                rows.append({
                    "scene": name, "method": method,
                    "seconds_median": statistics.median(times),
                    "seconds_min": min(times),
                    "trace_seconds_median": statistics.median(x["trace_seconds"]
                                                              for x in runs[method]),
                    "per_embree_median": statistics.median(ratios),
                    "per_embree_range": [min(ratios), max(ratios)],
                    "batches": runs[method][0]["batches"], "rays": runs[method][0]["rays"],
                    "passes": runs[method][0]["passes"],
                    "parts": {name: {"seconds_median": statistics.median(
                                         x["parts"][name]["seconds"] for x in runs[method]),
                                     "rays": part["rays"], "batches": part["batches"]}
                              for name, part in runs[method][0]["parts"].items()},
                })
    return rows


def table(rows):
    lines = ["| scene | method | render s (median) | trace s | x embree (median, range) | "
             "passes | batches | rays |", "|---|---|---:|---:|---:|---:|---:|---:|"]
    for r in rows:
        low, high = r["per_embree_range"]
        lines.append(f"| {r['scene']} | {r['method']} | {r['seconds_median']:.3f} | "
                     f"{r['trace_seconds_median']:.3f} | {r['per_embree_median']:.2f} "
                     f"({low:.2f}-{high:.2f}) | {r['passes']} | {r['batches']} | "
                     f"{r['rays']:,} |")
    return lines


def parts_table(rows):
    """Each part's median time for every method, and EDACRT's over Embree's."""
    lines = ["| scene | part | batches | rays (edacrt) | " +
             " | ".join(f"{m} ms" for m in METHODS) + " | edacrt / embree |",
             "|---|---|---:|---:|" + "---:|" * len(METHODS) + "---:|"]
    for scene in dict.fromkeys(r["scene"] for r in rows):
        by_method = {r["method"]: r["parts"] for r in rows if r["scene"] == scene}
        for name, part in sorted(by_method["edacrt"].items(), key=lambda p: PARTS.index(p[0])):
            ms = {m: 1e3 * by_method[m][name]["seconds_median"] if name in by_method[m] else None
                  for m in METHODS}
            cells = " | ".join("n/a" if v is None else f"{v:.1f}" for v in ms.values())
            ratio = (f"{ms['edacrt'] / ms['embree']:.2f}" if ms["embree"] else "n/a")
            batches, rays = (f"{part['batches']}", f"{part['rays']:,}") if part["rays"] else ("", "")
            lines.append(f"| {scene} | {name} | {batches} | {rays} | {cells} | {ratio} |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--scenes", type=Path, default=SCENES_DIR)
    parser.add_argument("--width", type=int, default=320)
    parser.add_argument("--height", type=int, default=240)
    parser.add_argument("--spp", type=int, default=8)
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--rounds", type=int, default=5)
    parser.add_argument("--quick", action="store_true",
                        help="the Cornell box, 64x48, 2 spp, one round")
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    args = parser.parse_args()
    command = "bench/render_bench.py " + " ".join(sys.argv[1:])
    if args.quick:
        args.width, args.height, args.spp, args.rounds = 64, 48, 2, 1
    scenes = scene_paths(args.scenes, ["cornell"] if args.quick else SCENES)
    missing = [str(p) for _, p in scenes if not p.is_file()]
    if missing:
        sys.exit("render_bench: missing scenes (give --scenes DIR): " + ", ".join(missing))
    started = time.time()
    rows = measure(args.build, scenes, args)
    out = ROOT / "out" / "render_bench" if args.quick else ROOT / "bench" / "results"
    out.mkdir(parents=True, exist_ok=True)
    result = out / f"render_bench_{time.strftime('%Y-%m-%d')}.json"
    settings = {k: getattr(args, k) for k in ("width", "height", "spp", "threads", "rounds")}
    result.write_text(json.dumps({"settings": settings, "rows": rows}, indent=1) + "\n")
    link = f"results/{result.name}" if not args.quick else str(result)
    section = "\n".join([
        HEADING, "",
        generated_line(command, seconds=time.time() - started), "",
        f"`edacrt render --integrator path --width {args.width} --height {args.height} --spp "
        f"{args.spp} --threads {args.threads}` on each scene's default view, every method, "
        f"{args.rounds} rounds in a shuffled order. `render s`: from the loaded scene to the "
        "finished image (the per-frame build of Embree and the BVH included, loading the OBJ "
        "not); `x embree`: the median of the per-round ratios to Embree's render, and their "
        f"range. The figures: [{result.name}]({link}). Issue 26's target is 1.00 or less for "
        "edacrt.", "", *table(rows), "",
        "Where the time goes: each part's median over the rounds (`prepare`: the per-frame "
        "triangle data or build; a bounce's batch holds the paths still alive, so after Russian "
        "roulette starts at bounce 3 the batches shrink; `shading and the rest`: the render's "
        "time outside the tracer). The ratio is of the medians.", "", *parts_table(rows), ""])
    if args.readme:
        splice(ROOT / "bench" / "README.md", HEADING, section)
    print(section)


if __name__ == "__main__":
    main()
