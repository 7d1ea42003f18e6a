#!/usr/bin/python3
"""Each method at its best: the switches that are not a method's identity, one at a time from
its defaults, timed per frame (set_scene + trace) with `edacrt bench` on camera, diffuse, AO and
shadow rays of the scenes of the list "bench" (assets/scenes.json), on 1 and 2 threads. The
defaults are checked against the best variant of every set: within 10% (issue 24).

Run from the repository root after building edacrt:
  bench/sweep.py --readme              (about 40 minutes on 2 cores)
  bench/sweep.py --quick               (64x64, one frame, two scenes: checks that it works)
  bench/sweep.py --from-results --readme   (re-make the section from out/sweep/*.json)
One `edacrt bench` process per scene and thread count runs every variant on the same rays,
frames interleaved in a shuffled order, and checks that all of them found the same hits.
"""
import argparse
import functools
import json
import math
import sys
import time
from pathlib import Path

from bench_common import ROOT, SCENES_DIR, run as run_checked, scene_list
from readme_section import generated_line, revision, splice

HEADING = "## Each method at its best: the switch sweep"
run = functools.partial(run_checked, tool="sweep")
SETS = ["camera-1spp", "diffuse", "ao", "shadow"]
TOLERANCE = 1.10  # a default within 10% of the best variant of every set
CONFIRM_REPEAT = 15  # frames of the head-to-head run that confirms better variants
SETTLE_REPEAT = 45  # frames of the run of a variant still better after it, alone with the default

# Per method, the variants: one switch each, away from the method's defaults. The identity of
# each (EDACRT: sampled ratios and order, filter skipping; DACRT: area ratios, direction-sign
# order, always filtering; the BVH: binned SAH, 8-wide) stays. The cost constants that cannot
# change a decision under the defaults (C_T and C_I cancel in the argmin without cost leaves;
# C_child needs filter-skip=triangles) are not swept.
VARIANTS = {
    "edacrt": ["second-child=after-first", "presplit=0", "presplit=0.3", "leaf-tris=4",
               "leaf-tris=16", "leaf-tris-rays=0", "leaf-tris-rays=64", "leaf-tris-rays=1024",
               "leaf-rays=8", "leaf-rays=32", "bins=4", "bins=16",
               "binning=centroids", "small-nodes=scaled", "small-nodes=capped",
               "small-nodes=every-ray", "small-nodes=surface-area", "sample-min=8",
               "sample-min=32", "sample-count=50", "sample-threshold=300", "far-child=unstopped",
               "cost-leaf-max-tris=64", "filter-skip=triangles", "c-bv=0.25", "c-bv=1"],
    "dacrt": ["second-child=after-first", "presplit=0", "presplit=0.3", "leaf-tris=4",
              "leaf-tris=16", "leaf-tris-rays=0", "leaf-tris-rays=64", "leaf-tris-rays=1024",
              "leaf-rays=8", "leaf-rays=32", "bins=4", "bins=16",
              "binning=centroids", "cost-leaf-max-tris=64"],
    "bvh": ["bins=8", "bins=16", "max-leaf=4", "max-leaf=16", "c-t=0.5", "c-t=2"],
}


def specs():
    """Every variant's --methods spec, the defaults first."""
    return [m for m in VARIANTS] + [f"{m}:{v}" for m, vs in VARIANTS.items() for v in vs]


def measure(args, scenes):
    """Runs (or, with --resume, reuses) one bench per scene and thread count; the rows."""
    rows = []
    for threads in args.threads:
        for name in scenes:
            path = args.out / f"{name}-{threads}t.json"
            if not (args.resume and path.exists()):
                print(f"sweep: {name}, {threads} thread(s)", file=sys.stderr, flush=True)
                run([args.build / "edacrt", "bench", "--scene", name, "--scenes", args.scenes,
                     "--sets", "camera,diffuse,ao,shadow", "--spp", "1",
                     "--width", args.size, "--height", args.size, "--repeat", args.repeat,
                     "--threads", threads, "--methods", ",".join(specs()), "--json", path, "-q"])
            bench = json.loads(path.read_text())
            for r in bench["results"]:
                rows.append({"scene": r["scene"], "set": r["set"], "threads": threads,
                             "variant": r["method"], "rays": r["rays"],
                             "frame": r["frame_seconds_median"],
                             "box": r["box_tests_per_ray"], "tri": r["triangle_tests_per_ray"]})
            machine = bench["machine"]
    return rows, machine


def bench_set(set_name):
    """The --sets and --spp of one of bench's set names ("camera-1spp", "diffuse", ...)."""
    if set_name.startswith("camera-"):
        return ["--sets", "camera", "--spp", set_name.split("-")[1].removesuffix("spp")]
    return ["--sets", set_name, "--spp", "1"]


def head_to_head(args, path, scene, set_, threads, specs, repeat):
    """One `edacrt bench` of `specs` on one set (or, with --resume, its stored run if it timed
    exactly these); each spec's median frame time."""
    stored = json.loads(path.read_text())["results"] if path.exists() else []
    if not (args.resume and {r["method"] for r in stored} == set(specs)):
        print(f"sweep: {', '.join(specs[1:])} against {specs[0]} on {scene} {set_}, "
              f"{threads} thread(s), {repeat} frames", file=sys.stderr, flush=True)
        run([args.build / "edacrt", "bench", "--scene", scene, "--scenes", args.scenes,
             *bench_set(set_), "--width", args.size, "--height", args.size,
             "--repeat", repeat, "--threads", threads, "--methods", ",".join(specs),
             "--json", path, "-q"])
    return {r["method"]: r["frame_seconds_median"]
            for r in json.loads(path.read_text())["results"]}


def confirm(args, rows):
    """The best of many noisy variants is biased low (the luckiest of 20), and one slow frame of
    the default's makes every variant of its set look better. Where variants beat their
    method's defaults by more than TOLERANCE, all of them run again with the defaults head to
    head, on that set alone, for CONFIRM_REPEAT frames. A variant still better by more than
    TOLERANCE then runs alone with the defaults for SETTLE_REPEAT frames (as many draws of
    EDACRT's samples: on frames of 5-15 ms one draw's tree can take 0.8-1.3x another's), and
    that ratio counts. Returns {(method, threads, scene, set): {variant: ratio}}."""
    confirmed = {}
    for key, c in sorted(analyse(rows).items()):
        method, threads, scene, set_ = key
        better = sorted(v for v, ratio in c.items() if 1.0 / ratio > TOLERANCE)
        if not better:
            continue
        name = f"{scene}-{set_}-{threads}t-{method}"
        again = head_to_head(args, args.out / f"confirm-{name}.json", scene, set_, threads,
                             [method, *better], CONFIRM_REPEAT)
        ratios = {v: again[v] / again[method] for v in better}
        for v, ratio in ratios.items():
            if 1.0 / ratio > TOLERANCE:
                label = v.split(":", 1)[1].replace("=", "-")
                alone = head_to_head(args, args.out / f"settle-{name}-{label}.json", scene,
                                     set_, threads, [method, v], SETTLE_REPEAT)
                ratios[v] = alone[v] / alone[method]
        confirmed[key] = ratios
    return confirmed


def method_of(variant):
    return variant.split(":")[0]


def analyse(rows, confirmed=None):
    """Per (method, threads, scene, set): each variant's frame time over the default's, the
    confirmed ratios in place of the sweep's."""
    frames = {(r["threads"], r["scene"], r["set"], r["variant"]): r for r in rows}
    cells = {}
    for (threads, scene, set_, variant), r in frames.items():
        base = frames.get((threads, scene, set_, method_of(variant)))
        if base:
            cells.setdefault((method_of(variant), threads, scene, set_), {})[variant] = (
                r["frame"] / base["frame"])
    for key, ratios in (confirmed or {}).items():
        cells[key].update(ratios)
    return cells


def geomean(values):
    return math.exp(sum(math.log(v) for v in values) / len(values)) if values else float("nan")


def markdown(args, rows, confirmed, machine, seconds, command, rev):
    cells = analyse(rows, confirmed)
    threads = sorted({r["threads"] for r in rows})
    scenes = list(dict.fromkeys(r["scene"] for r in rows))
    lines = [HEADING, "",
             generated_line(command, machine, seconds, rev,
                            " Remade from its stored results (`--from-results`)."
                            if args.from_results else ""),
             "",
             f"Each method's switches, one at a time away from its defaults, timed per frame "
             f"(`set_scene()` + `trace()`, medians of {args.repeat} frames interleaved in a "
             f"shuffled order in one `edacrt bench` process per scene and thread count; frame r "
             f"draws EDACRT's ray samples with sampling seed 1 + r, since one draw's tree can "
             f"take 0.8-1.3x the time of another's) on "
             f"{args.size}x{args.size} pixels: jittered camera rays (1 spp) and, from their hits, "
             f"diffuse bounces, AO and shadow rays; scenes {', '.join(scenes)}. Every variant "
             f"found the same hits (bench's agreement check). A cell is the variant's frame time "
             f"over the default's: below 1.00 is faster. Read ratios, not absolute times: "
             f"the machine is shared and noisy (about 5% between identical runs).",
             ""]
    for method in VARIANTS:
        lines += [f"**{method}**: frame time over the default's, geometric mean over the "
                  f"{len(scenes) * len(SETS)} sets (min - max)", "",
                  "| variant | " + " | ".join(f"{t} thread{'s' if t > 1 else ''}"
                                              for t in threads) + " |",
                  "|---|" + "---:|" * len(threads)]
        for variant in [method] + [f"{method}:{v}" for v in VARIANTS[method]]:
            row = [variant.split(":", 1)[1] if ":" in variant else "(defaults)"]
            for t in threads:
                ratios = [c[variant] for (m, tt, _, _), c in cells.items()
                          if m == method and tt == t and variant in c]
                row.append(f"{geomean(ratios):.2f} ({min(ratios):.2f} - {max(ratios):.2f})"
                           if ratios else "-")
            lines.append("| " + " | ".join(row) + " |")
        lines.append("")
    lines += ["**The defaults against the best variant of each set**: the largest default / "
              "best frame time over the sets, where, and which variant was best there (the "
              f"goal: at most {TOLERANCE:.2f}).", "",
              "| method | threads | worst default / best | set | best variant there | sets "
              f"within {TOLERANCE:.2f} |", "|---|---:|---:|---|---|---:|"]
    worst_all = 1.0
    for method in VARIANTS:
        for t in threads:
            mine = {(s, st): c for (m, tt, s, st), c in cells.items() if m == method and tt == t}
            if not mine:
                continue
            worst, where, best_variant, within = 0.0, "", "", 0
            for (scene, set_), c in mine.items():
                variant = min(c, key=c.get)
                ratio = 1.0 / c[variant]
                within += ratio <= TOLERANCE
                if ratio > worst:
                    worst, where, best_variant = ratio, f"{scene} {set_}", variant
            worst_all = max(worst_all, worst)
            lines.append(f"| {method} | {t} | {worst:.2f} | {where} | "
                         f"{best_variant.split(':', 1)[-1] if ':' in best_variant else '-'} | "
                         f"{within} / {len(mine)} |")
    beyond = {}  # (method, variant): [(ratio, scene, set, threads)], where it beats the default
    for (m, t, scene, set_), c in sorted(cells.items()):
        variant = min(c, key=c.get)
        if 1.0 / c[variant] > TOLERANCE:
            beyond.setdefault((m, variant), []).append((c[variant], scene, set_, t))
    if beyond:
        lines += ["", f"**Where a variant beats the defaults by more than {TOLERANCE:.2f}** "
                  "(after the head-to-head runs; the variant's frame time over the default's, "
                  "1t/2t for 1 and 2 threads):", "",
                  "| method | variant | sets |", "|---|---|---|"]
        for (m, variant), where in sorted(beyond.items(), key=lambda kv: -len(kv[1])):
            lines.append(f"| {m} | {variant.split(':', 1)[-1]} | " + ", ".join(
                f"{scene} {set_} {t}t {r:.2f}" for r, scene, set_, t in sorted(where)) + " |")
    lines += ["", f"Where a variant beat the defaults by more than {TOLERANCE:.2f} in the "
              f"sweep, all such variants of the set ran again with the defaults head to head for "
              f"{CONFIRM_REPEAT} frames (the best of some twenty noisy variants is biased low, "
              "and one slow frame of the default's flatters all of them), and those times count; "
              f"a variant still better by more than {TOLERANCE:.2f} ran alone with the defaults "
              f"for {SETTLE_REPEAT} frames (as many draws of EDACRT's samples), and that time "
              "counts. "
              "On one thread `second-child=after-first` is the default's recursion (split "
              "starts no task there): its ratios show the noise.",
              "", "Per set, the counters behind the times (tests per ray, the defaults): "
              "`out/sweep/*.json` after a run; the compact results are in "
              "[results/sweep.json](results/sweep.json).", ""]
    return "\n".join(lines), worst_all


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--scenes", type=Path,
                        default=SCENES_DIR)
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "sweep")
    parser.add_argument("--size", type=int, default=512, help="image width and height")
    parser.add_argument("--repeat", type=int, default=5, help="timed frames per variant")
    parser.add_argument("--threads", default="1,2", help="thread counts, comma-separated")
    parser.add_argument("--scene", action="append", help="only this scene (repeatable)")
    parser.add_argument("--quick", action="store_true",
                        help="64x64, one frame, cornell and teapot: a smoke test")
    parser.add_argument("--resume", action="store_true",
                        help="keep the benches of an interrupted run (out/sweep/*.json)")
    parser.add_argument("--from-results", action="store_true",
                        help="no measuring: the section from out/sweep/*.json")
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    args = parser.parse_args()
    command = "bench/sweep.py " + " ".join(sys.argv[1:])
    args.threads = [int(t) for t in args.threads.split(",")]
    if args.quick:
        args.size, args.repeat, args.out = 64, 1, args.out / "quick"
        args.scene = args.scene or ["cornell", "teapot"]
    scenes = args.scene or [s.name for s in scene_list("bench")]
    args.out.mkdir(parents=True, exist_ok=True)
    started = time.time()
    if args.from_results:
        args.resume = True
        if not any(args.out.glob("*.json")):
            sys.exit(f"sweep: no results in {args.out}; run without --from-results first")
        scenes = [s for s in scenes if any(args.out.glob(f"{s}-*t.json"))]
    rows, machine = measure(args, scenes)
    confirmed = {} if args.quick else confirm(args, rows)
    # What measured: the section names it, also when remade from the stored results.
    meta_path = args.out / "measured.json"
    if not args.from_results:
        meta_path.write_text(json.dumps({"revision": revision(), "command": command,
                                         "seconds": round(time.time() - started)}))
    meta = json.loads(meta_path.read_text()) if meta_path.exists() else {}
    if args.from_results:
        command = meta.get("command", "bench/sweep.py")
    section, worst = markdown(args, rows, confirmed, machine, meta.get("seconds"), command,
                              meta.get("revision"))
    (args.out / "sweep.md").write_text(section)
    if not args.quick:
        (ROOT / "bench" / "results" / "sweep.json").write_text(
            json.dumps({"machine": machine, "revision": meta.get("revision"), "size": args.size,
                        "repeat": args.repeat, "confirmed": [
                            {"method": k[0], "threads": k[1], "scene": k[2], "set": k[3],
                             "ratios": v} for k, v in confirmed.items()],
                        "rows": rows}, indent=0) + "\n")
    if args.readme:
        splice(ROOT / "bench" / "README.md", HEADING, section)
    print(section)
    print(f"sweep: the worst default is {worst:.2f}x its set's best "
          f"({'within' if worst <= TOLERANCE else 'beyond'} {TOLERANCE:.2f})", file=sys.stderr)


if __name__ == "__main__":
    main()
