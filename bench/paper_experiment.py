#!/usr/bin/python3
"""EDACRT against DACRT, the paper's experiment (Nabata et al., "Efficient Divide-And-Conquer
Ray Tracing using Ray Sampling", HPG 2013): per scene and ray set, the trace time of DACRT, of
EDACRT (defaults and the paper preset), and of ablations that add one EDACRT contribution to
DACRT or remove one from EDACRT. Writes out/paper/paper_experiment.md, out/paper/results.json
and bench/figures/paper_speedup.png; --readme puts the section into bench/README.md.

Run from the repository root after building edacrt and edacrt_paper_rays:
  bench/paper_experiment.py --readme          (about 40 minutes on 2 cores)
  bench/paper_experiment.py --quick           (64x64, one run: checks that it works)
  bench/paper_experiment.py --from-results --readme   (re-make the section from results.json)
Time is the trace_seconds `edacrt trace` prints (one batch; file I/O and scene set-up are
outside it); variants run interleaved, the median of --repeats runs is reported. Run r draws
EDACRT's ray samples with --sampling-seed 1 + r: the tree depends on the draw, so medians and
the mean counters are over draws, not one seed's luck.
"""
import argparse
import functools
import json
import math
import os
import re
import shlex
import statistics
import sys
import time
from pathlib import Path

from bench_common import ROOT, SCENES_DIR, run as run_checked, scene_list
from readme_section import generated_line, revision, splice

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HEADING = "## EDACRT against DACRT (the paper's experiment)"
run = functools.partial(run_checked, tool="paper_experiment")
RAY_SETS = ["camera_1spp", "camera_4spp", "camera_16spp", "diffuse", "reflection", "path"]
SPP = {"camera_1spp": 1, "camera_4spp": 4, "camera_16spp": 16}
EDACRT = ["--method", "edacrt"]
DACRT_ON_EDACRT = EDACRT + ["--preset", "dacrt"]  # --method dacrt would override the flags
VARIANTS = [  # key, label, edacrt trace flags, ablation (else measured on every ray set)
    ("dacrt", "DACRT", ["--method", "dacrt"], False),
    ("edacrt", "EDACRT (defaults)", EDACRT, False),
    ("paper", "EDACRT, --preset paper", EDACRT + ["--preset", "paper"], False),
    ("dacrt-paper", "DACRT as published", ["--method", "dacrt", "--presplit", "0",
                                           "--second-child", "after-first", "--leaf-tris", "4",
                                           "--leaf-tris-rays", "0"], False),
    ("dacrt+ratio", "DACRT + sampled hit ratio", DACRT_ON_EDACRT + ["--hit-ratio", "sampled"],
     True),
    ("dacrt+order", "DACRT + sampled order", DACRT_ON_EDACRT + ["--order", "sampled"], True),
    ("dacrt+skip", "DACRT + filter skipping", DACRT_ON_EDACRT + ["--filter-skip", "paper"], True),
    ("edacrt-ratio", "EDACRT, area hit ratio", EDACRT + ["--hit-ratio", "surface-area"], True),
    ("edacrt-order", "EDACRT, direction-sign order", EDACRT + ["--order", "direction-sign"], True),
    ("edacrt-skip", "EDACRT, no filter skipping", EDACRT + ["--filter-skip", "off"], True),
    ("edacrt-small", "EDACRT, small nodes every-ray", EDACRT + ["--small-nodes", "every-ray"],
     True),
]
LABEL = {key: label for key, label, _, _ in VARIANTS}
# The two comparisons: (name, DACRT variant, EDACRT variant). Each at its best: both methods'
# defaults (set from bench/sweep.py). As in the paper: the paper preset against DACRT as Mora
# 2011 and Afra 2012 define it, without our pre-split triangles, the second child after the
# first.
COMPARISONS = [("each at its best", "dacrt", "edacrt"),
               ("as in the paper", "dacrt-paper", "paper")]
ABLATIONS_FROM = next(i for i, v in enumerate(VARIANTS) if v[3])


def make_rays(args, name, scene, camera_flags):
    """The scene's ray files (regenerated every run: a few seconds); {set: (path, rays)}."""
    directory = args.out / "rays" / name
    run(["nice", args.build / "edacrt_paper_rays", "--scene", scene, "--width", args.size,
         "--height", args.size, "--out-dir", directory, *camera_flags])
    paths = {s: directory / f"{s}.rays" for s in RAY_SETS}
    return {s: (p, p.stat().st_size // 32) for s, p in paths.items()}


def trace(args, scene, rays, flags, seed, stats=None):
    """One `edacrt trace` with sampling seed `seed`: the timed pass's seconds, box and triangle
    tests, and with `stats` its JSON (detail from an extra untimed pass)."""
    command = ["nice", args.build / "edacrt", "trace", "--scene", scene, "--rays", rays,
               "--out", "/dev/null", "--threads", args.threads, "--sampling-seed", seed, *flags]
    text = run(command + (["--stats", stats] if stats else []))
    match = re.search(r" in ([0-9.eE+-]+) s:.* ([0-9]+) ray-box and ([0-9]+) ray-triangle", text)
    seconds, box, tri = float(match.group(1)), int(match.group(2)), int(match.group(3))
    return seconds, box, tri, json.loads(stats.read_text()) if stats else None


def summarise_detail(data):
    """Counters that explain a time: per ray, and over the recursion's levels."""
    n = max(data["rays"], 1)
    levels, root = data["detail"]["levels"], data["detail"]["root"]
    total = {k: sum(level[k] for level in levels)
             for k in ("order_hits", "order_misses", "filters_done", "filters_skipped",
                       "sample_box_tests", "filter_box_tests", "culled_by_distance",
                       "alpha_children", "ray_triangle_tests", "leaves", "nodes")}
    alpha_error = sum(level["alpha_error_mean"] * level["alpha_children"] for level in levels)
    ordered = total["order_hits"] + total["order_misses"]
    filters = total["filters_done"] + total["filters_skipped"]
    return {
        "order_first": total["order_hits"] / ordered if ordered else float("nan"),
        "filters_skipped": total["filters_skipped"] / filters if filters else float("nan"),
        "sample_box_per_ray": total["sample_box_tests"] / n,
        "filter_box_per_ray": (total["filter_box_tests"] + root["box_tests"]) / n,
        "culled_per_ray": total["culled_by_distance"] / n,
        "alpha_error": alpha_error / max(total["alpha_children"], 1),
        "depth": len(levels),
        "leaves": total["leaves"],
    }


def measure_set(args, scene, rays, count, variants, stats_dir):
    """Every variant on one ray file, interleaved: run r visits the variants rotated by r."""
    results = {key: {"times": [], "box": [], "tri": []} for key in variants}
    for r in range(args.repeats):
        order = variants[r % len(variants):] + variants[:r % len(variants)]
        for key in order:
            flags = next(f for k, _, f, _ in VARIANTS if k == key)
            stats = stats_dir / f"{key}.json" if r == 0 else None
            seconds, box, tri, data = trace(args, scene, rays, flags, 1 + r, stats)
            for name, value in (("times", seconds), ("box", box), ("tri", tri)):
                results[key][name].append(value)
            if data:  # the first run (seed 1): the detail
                results[key]["detail"] = summarise_detail(data)
    for key in variants:
        v = results[key]
        v["median"] = statistics.median(v["times"])
        v["box_per_ray"] = statistics.mean(v.pop("box")) / max(count, 1)
        v["tri_per_ray"] = statistics.mean(v.pop("tri")) / max(count, 1)
    return results


def measure(args, previous):
    """Measures every scene, or only the --scene ones, keeping the others from `previous`."""
    settings = {"size": args.size, "repeats": args.repeats, "threads": args.threads,
                "ablation_sets": args.ablation_sets}
    results = {**settings, "scenes": {}, "runs": [], "skipped": []}
    if args.scene and previous:
        if any(previous[k] != v for k, v in settings.items()):
            sys.exit("paper_experiment: --scene keeps the other scenes of results.json, which "
                     f"were measured with other settings ({ {k: previous[k] for k in settings} })")
        results["scenes"] = {n: s for n, s in previous["scenes"].items() if n not in args.scene}
        runs = [dict(r, scenes=[n for n in r["scenes"] if n not in args.scene])
                for r in previous["runs"]]
        results["runs"] = [r for r in runs if r["scenes"]]
        results["skipped"] = [s for s in previous["skipped"] if s.split()[0] not in args.scene]
    argv = sys.argv[1:]
    if "--note" in argv:  # the note is shown apart
        del argv[argv.index("--note"):argv.index("--note") + 2]
    argv = [a for a in argv if not a.startswith("--note=")]
    run = {"command": "bench/paper_experiment.py " + shlex.join(argv), "note": args.note,
           "revision": revision(),
           "started": time.time(), "load_before": os.getloadavg()[0], "scenes": []}
    scenes = scene_list("paper")
    for entry in scenes:
        name, camera_flags = entry.name, entry.camera_flags
        if args.scene and name not in args.scene:
            continue
        scene = entry.path(args.scenes)
        if not scene.exists():
            print(f"{name}: {scene} not found, skipped", flush=True)
            results["skipped"].append(f"{name} ({scene} not found)")
            continue
        sets = make_rays(args, name, scene, camera_flags)
        results["scenes"][name] = {}
        run["scenes"].append(name)
        for ray_set, (path, count) in sets.items():
            if count == 0:
                results["skipped"].append(f"{name} {ray_set} (no rays)")
                continue
            variants = [k for k, _, _, ablation in VARIANTS
                        if not ablation or ray_set in args.ablation_sets]
            stats_dir = args.out / "stats" / name / ray_set
            stats_dir.mkdir(parents=True, exist_ok=True)
            measured = measure_set(args, scene, path, count, variants, stats_dir)
            results["scenes"][name][ray_set] = {"rays": count, "variants": measured}
            d, e = measured["dacrt"]["median"], measured["edacrt"]["median"]
            print(f"{name} {ray_set} ({count:,} rays): dacrt {1e3 * d:.0f} ms, edacrt "
                  f"{1e3 * e:.0f} ms, speed-up {d / e:.2f}", flush=True)
    run.update(seconds=time.time() - run["started"], load_after=os.getloadavg()[0])
    results["runs"].append(run)
    results["scenes"] = {n: results["scenes"][n] for n, *_ in scenes if n in results["scenes"]}
    return results


def speedup(cell, key, base="dacrt"):
    return cell["variants"][base]["median"] / cell["variants"][key]["median"]


def geomean(values):
    return math.exp(sum(map(math.log, values)) / len(values)) if values else float("nan")


def plot(results, path):
    fig, ax = plt.subplots(figsize=(8.5, 4.2), dpi=110)
    for i, (name, sets) in enumerate(results["scenes"].items()):
        cells = [(SPP[s], sets[s]) for s in SPP if s in sets]
        for (what, base, key), style in zip(COMPARISONS, ("-o", "--s")):
            ax.plot([spp for spp, _ in cells], [speedup(c, key, base) for _, c in cells], style,
                    color=f"C{i}", label=f"{name}, {what}")
    ax.axhline(1.0, color="gray", linewidth=0.8)
    ax.axhline(2.0, color="gray", linewidth=0.8, linestyle=":", label="the paper's 'up to 2x'")
    ax.set_xscale("log", base=2)
    ax.set_xticks([1, 4, 16], ["1", "4", "16"])
    ax.set_xlabel("camera rays per pixel")
    ax.set_ylabel("EDACRT's speed-up over DACRT")
    ax.set_title(f"EDACRT against DACRT, camera rays at {results['size']}x{results['size']}")
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.02, 1.0))
    fig.tight_layout()
    fig.savefig(path)
    plt.close(fig)


def fmt(x, digits=2):
    return "n/a" if x is None or (isinstance(x, float) and math.isnan(x)) else f"{x:.{digits}f}"


def main_table(results):
    """Both comparisons side by side, with the counters behind each time."""
    head = "| scene | rays | count |"
    rule = "|---|---|---:|"
    for what, base, key in COMPARISONS:
        head += (f" {LABEL[base]} ms | {LABEL[key]} ms | speed-up, {what} | tri/ray | box/ray |")
        rule += "---:|---:|---:|---:|---:|"
    lines = [head, rule]
    for name, sets in results["scenes"].items():
        for ray_set, cell in sets.items():
            v = cell["variants"]
            row = f"| {name} | {ray_set} | {cell['rays']:,} |"
            for _, base, key in COMPARISONS:
                row += (f" {1e3 * v[base]['median']:.0f} | {1e3 * v[key]['median']:.0f} | "
                        f"**{speedup(cell, key, base):.2f}** | "
                        f"{v[base]['tri_per_ray']:.0f} -> {v[key]['tri_per_ray']:.0f} | "
                        f"{v[base]['box_per_ray']:.0f} -> {v[key]['box_per_ray']:.0f} |")
            lines.append(row)
    return lines


def ablation_table(results):
    cells = [(name, s, c) for name, sets in results["scenes"].items() for s, c in sets.items()
             if len(c["variants"]) == len(VARIANTS)]
    lines = ["| variant | " + " | ".join(f"{n} {s}" for n, s, _ in cells) + " | geo. mean | "
             "tri/ray vs DACRT | box/ray vs DACRT | filters skipped | first child right |",
             "|---|" + "---:|" * (len(cells) + 5)]
    for key, label, _, _ in VARIANTS:
        v = [c["variants"][key] for _, _, c in cells]
        d = [c["variants"]["dacrt"] for _, _, c in cells]
        values = [speedup(c, key) for _, _, c in cells]
        lines.append(
            f"| {label} | " + " | ".join(f"{x:.2f}" for x in values) +
            f" | **{geomean(values):.2f}** | "
            f"{geomean([a['tri_per_ray'] / b['tri_per_ray'] for a, b in zip(v, d)]):.2f} | "
            f"{geomean([a['box_per_ray'] / b['box_per_ray'] for a, b in zip(v, d)]):.2f} | "
            f"{100 * statistics.mean(a['detail']['filters_skipped'] for a in v):.0f}% | "
            f"{100 * statistics.mean(a['detail']['order_first'] for a in v):.0f}% |")
    return lines, cells


def counter_table(results):
    lines = ["| scene | rays | variant | first child right | filters skipped | sample box/ray | "
             "filter box/ray | culled by distance/ray | mean abs alpha error | levels |",
             "|---|---|---|---:|---:|---:|---:|---:|---:|---:|"]
    for name, sets in results["scenes"].items():
        for ray_set, cell in sets.items():
            for key in ("dacrt", "edacrt", "dacrt-paper", "paper"):
                d = cell["variants"][key]["detail"]
                lines.append(
                    f"| {name} | {ray_set} | {key} | {100 * d['order_first']:.0f}% | "
                    f"{100 * d['filters_skipped']:.0f}% | {d['sample_box_per_ray']:.1f} | "
                    f"{d['filter_box_per_ray']:.0f} | {d['culled_per_ray']:.2f} | "
                    f"{fmt(d['alpha_error'], 3)} | {d['depth']} |")
    return lines


def trend(values):
    """How a speed-up changes over 1, 4, 16 spp, allowing 3% noise per step."""
    first, middle, last = values
    rising = middle >= 0.97 * first and last >= 0.97 * middle
    falling = middle <= 1.03 * first and last <= 1.03 * middle
    if rising and last > 1.05 * first:
        return "grows"
    if falling and last < 0.95 * first:
        return "falls"
    if (rising or falling) and abs(last / first - 1) <= 0.05:
        return "flat"
    return "up and down"


def explain(cell, base, key):
    """Why EDACRT (`key`) is slower than DACRT (`base`) on one set, from their counters."""
    b, e = cell["variants"][base], cell["variants"][key]
    bd, ed = b["detail"], e["detail"]
    tri_saved = b["tri_per_ray"] - e["tri_per_ray"]
    filter_saved = bd["filter_box_per_ray"] - ed["filter_box_per_ray"]
    sampling = ed["sample_box_per_ray"] - bd["sample_box_per_ray"]
    facts = (f"triangle tests per ray {b['tri_per_ray']:.0f} -> {e['tri_per_ray']:.0f}, filter "
             f"box tests {bd['filter_box_per_ray']:.0f} -> {ed['filter_box_per_ray']:.0f}, "
             f"sampling box tests {sampling:.0f}, first child right "
             f"{100 * bd['order_first']:.0f}% -> {100 * ed['order_first']:.0f}%, filters skipped "
             f"{100 * ed['filters_skipped']:.0f}%")
    if tri_saved < -0.03 * b["tri_per_ray"]:
        why = ("its splits, chosen on sampled ratios, test more triangles than the area-ratio "
               "ones" + (" (without pre-split pieces, as [inside Sponza](#why-sampled-hit-ratios-"
                         "raise-the-work-inside-sponza-without-pre-split-pieces))"
                         if base == "dacrt-paper" else ""))
    elif sampling > tri_saved + filter_saved:
        why = (f"sampling costs {sampling:.0f} box tests per ray, more than the "
               f"{max(tri_saved, 0):.0f} triangle and {filter_saved:.0f} filter box tests it "
               "saves")
    else:
        why = ("the counters favour EDACRT; the time goes where they do not look (drawing the "
               "samples, the extra partition passes, smaller leaves)")
    return f"{facts}: {why}"


def comparison(results, ablation_cells):
    """Both comparisons against the paper's claim, in paragraphs computed from the tables."""
    scenes = results["scenes"]
    cells = [(n, s, c) for n, sets in scenes.items() for s, c in sets.items()]
    if not cells:
        return ["No scene was measured."]
    out = ["The paper reports EDACRT up to about 2x faster than DACRT, the gap growing with the "
           "number of rays per pixel."]
    for what, base, key in COMPARISONS:
        gains = [speedup(c, key, base) for _, _, c in cells]
        best = max(cells, key=lambda x: speedup(x[2], key, base))
        text = (f"**{what.capitalize()}** ({LABEL[key]} against {LABEL[base]}): the speed-up "
                f"is {min(gains):.2f}x to {max(gains):.2f}x, largest on {best[0]} {best[1]}, "
                f"geometric mean {geomean(gains):.2f}x over {len(cells)} scene and ray-set "
                "pairs.")
        trends = []
        for name, sets in scenes.items():
            values = [speedup(sets[s], key, base) for s in SPP if s in sets]
            if len(values) == 3:
                trends.append(f"{name} {' -> '.join(f'{v:.2f}' for v in values)} "
                              f"({trend(values)})")
        if trends:
            growing = sum(t.endswith("(grows)") for t in trends)
            text += (" Camera rays at 1, 4 and 16 samples per pixel: " + "; ".join(trends) +
                     f"; the growth with rays per pixel shows on {growing} of {len(trends)} "
                     "scenes.")
        slower = [x for x in cells if speedup(x[2], key, base) < 0.97]
        if slower:
            text += (f" EDACRT is slower (by more than 3%) on {len(slower)} of {len(cells)} "
                     "pairs; from the counters (per ray, DACRT -> EDACRT):")
            out.append(text)
            out.append("\n".join(f"- {n} {s} ({speedup(c, key, base):.2f}x): "
                                 f"{explain(c, base, key)}." for n, s, c in slower))
        else:
            out.append(text + " EDACRT is at least as fast (within 3%) on every pair.")
    # "At its best" holds only where DACRT's defaults are not beaten by DACRT as published.
    worse = [(n, st, speedup(c, "dacrt-paper")) for n, st, c in cells
             if speedup(c, "dacrt-paper") > 1.10]
    if worse:
        out.append("DACRT's defaults are not its best everywhere: DACRT as published (no "
                   "pre-split pieces, the second child after the first) is faster by more than "
                   "10% on " + ", ".join(f"{n} {st} ({1 / g:.2f}x the time)" for n, st, g in worse)
                   + ", so EDACRT's speed-up there is against a slower DACRT than it could be "
                   "([the sweep](#each-method-at-its-best-the-switch-sweep) finds the same for "
                   "`presplit=0`).")
    if ablation_cells:
        gains = {k: geomean([speedup(c, k) for _, _, c in ablation_cells])
                 for k, _, _, _ in VARIANTS}
        out.append(
            "Ablations (geometric mean over the ablation ray sets, speed-up over DACRT): alone on "
            "DACRT, " + ", ".join(f"{label.removeprefix('DACRT + ')} {gains[k]:.2f}x"
                                  for k, label, _, _ in VARIANTS[ABLATIONS_FROM:
                                                                 ABLATIONS_FROM + 3]) +
            f"; EDACRT with all of them {gains['edacrt']:.2f}x, and with one taken back " +
            ", ".join(f"{label.removeprefix('EDACRT, ')} {gains[k]:.2f}x"
                      for k, label, _, _ in VARIANTS[ABLATIONS_FROM + 3:]) +
            ". A contribution pays where adding it to DACRT raises the speed-up above 1 and "
            "taking it from EDACRT lowers it; filter skipping decides on the hit ratio, so it "
            "is only as good as the ratio it is given (compare its triangle tests per ray with "
            "area ratios and with sampled ones).")
    return "\n\n".join(out).split("\n")


def markdown(args, results, figure):
    scenes = ", ".join(results["scenes"]) or "none"
    cpu = next((line.split(":", 1)[1].strip() for line in open("/proc/cpuinfo")
                if line.startswith("model name")), "unknown CPU")
    spreads = [(max(v["times"]) - min(v["times"])) / v["median"]
               for sets in results["scenes"].values() for c in sets.values()
               for v in c["variants"].values() if len(v["times"]) > 1]
    runs = "; ".join(
        f"`{r['command']}` ({time.strftime('%Y-%m-%d', time.localtime(r['started']))}, "
        f"{r['seconds'] / 60:.0f} min, load average {r['load_before']:.1f} at the start and "
        f"{r['load_after']:.1f} at the end): {', '.join(r['scenes'])}"
        + (f" ({r['note']})" if r.get("note") else "") for r in results["runs"])
    lines = [
        HEADING,
        "",
        generated_line("bench/paper_experiment.py --readme", rev=results["runs"][-1].get("revision")),
        "",
        f"Runs: {runs}. Machine: {cpu}, {os.cpu_count()} hardware threads, "
        f"`--threads {results['threads']}` (the machine is shared: read ratios of one run, not "
        "absolute times)"
        + (f"; the median spread (max - min) / median of a variant's runs is "
           f"{100 * statistics.median(spreads):.0f}%." if spreads else ".")
        + (f" Skipped: {'; '.join(results['skipped'])}." if results["skipped"] else ""),
        "",
        f"Scenes: {scenes}. Rays from `edacrt_paper_rays` (bench/paper_rays.cpp) at "
        f"{results['size']}x{results['size']}: jittered camera rays at 1, 4 and 16 samples per "
        "pixel (all samples of a pixel together), and from the hits of the 1-spp camera rays one "
        "cosine-distributed `diffuse` ray, one mirror `reflection` ray, and `path`: bounces 2 "
        "and 3 of diffuse path tracing (`diffuse` is bounce 1). The bunny is framed from +z, the "
        "buildings are seen from inside (views in bench/paper_experiment.py). Each file is one "
        "`edacrt trace` batch (closest hit); time is its trace_seconds, the median of "
        f"{results['repeats']} runs with the variants interleaved, run r with `--sampling-seed "
        "1+r` (a tree depends on its draw of sampled rays; one seed's tree can take 0.8-1.3x the "
        "time of another's); counters are per ray, the mean over the runs of the timed pass's "
        "totals (box tests include EDACRT's sampling).",
        "",
        "Two comparisons. **Each at its best**: `--method dacrt` against `--method edacrt`, "
        "each with its own defaults, which [the sweep](#each-method-at-its-best-the-switch-sweep) "
        "chose (DACRT is surface-area hit ratios, direction-sign order and always filtering on "
        "the same recursion). **As in the paper**: EDACRT's `--preset paper` (every ray sampled "
        "in nodes of at most 1000 rays, the second child after the first, no pre-split "
        "triangles, leaves of 4 triangles whatever their rays) against DACRT as Mora 2011 and "
        "Afra 2012 define it: `--method dacrt --presplit 0 --second-child after-first "
        "--leaf-tris 4 --leaf-tris-rays 0`. The paper's own K, leaf thresholds and cost "
        "constants are not in the report the project started from; both sides use ours (K = 8, "
        "16 rays or 4 triangles per leaf, C_T = 2, C_I = 1, C_bv = 0.5).",
        "",
        f"![speed-up against samples per pixel](figures/{figure.name})",
        "",
        *main_table(results),
        "",
        "### Ablations",
        "",
    ]
    ablation_lines, ablation_cells = ablation_table(results)
    lines += [
        "Speed-up over DACRT (DACRT time / variant time, medians) of each EDACRT contribution "
        "added to DACRT (`--method edacrt --preset dacrt` plus the flag) and taken from EDACRT "
        "(`--method edacrt` plus the flag). `small nodes every-ray` is the paper's choice in "
        "place of the default cap of sample-count rays. Ray sets: "
        f"{', '.join(args.ablation_sets)}.",
        "",
        *ablation_lines,
        "",
        "### Counters behind the times",
        "",
        "From the `--stats` detail (an extra, untimed pass of the first run, sampling seed 1). "
        "*First child "
        "right*: among rays that hit both children's boxes, the share whose hit was in the child "
        "visited first. *Filters skipped*: child ray sets passed down unfiltered. *Sample box*: "
        "box tests of the sampled rays; *filter box*: box tests of the filtering (root "
        "included). *Culled by distance*: rays the second child's filter dropped because their "
        "hit was already nearer. *Alpha error*: |estimated - true| hit ratio of the chosen "
        "children.",
        "",
        *counter_table(results),
        "",
        "### Against the paper",
        "",
        *comparison(results, ablation_cells),
        "",
        "Reproduce: build `edacrt` and `edacrt_paper_rays`, then `bench/paper_experiment.py "
        "--readme` (`--quick` for a smoke run, `--from-results --readme` to remake this section "
        "from out/paper/results.json).",
        "",
    ]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--scenes", type=Path, default=SCENES_DIR)
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "paper")
    parser.add_argument("--size", type=int, default=512, help="image width and height")
    parser.add_argument("--repeats", type=int, default=5, help="timed runs per variant")
    parser.add_argument("--threads", type=int, default=2)
    parser.add_argument("--scene", action="append",
                        help="measure only this scene (repeatable); the others are kept from "
                             "results.json")
    parser.add_argument("--note", default="", help="a remark on this run, for the section")
    parser.add_argument("--ablation-sets", default="camera_4spp,diffuse",
                        help="ray sets the ablations run on (comma-separated; 'all')")
    parser.add_argument("--quick", action="store_true", help="64x64, one run: a smoke test")
    parser.add_argument("--from-results", action="store_true",
                        help="no measuring: the section and figure from out/paper/results.json")
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    args = parser.parse_args()
    if args.quick:
        args.size, args.repeats = 64, 1
    args.ablation_sets = RAY_SETS if args.ablation_sets == "all" else args.ablation_sets.split(",")
    if unknown := set(args.ablation_sets) - set(RAY_SETS):
        sys.exit(f"paper_experiment: unknown ray sets {sorted(unknown)}; known: {RAY_SETS}")
    args.out.mkdir(parents=True, exist_ok=True)
    cache = args.out / ("results_quick.json" if args.quick else "results.json")

    if args.from_results:
        if not cache.exists():
            sys.exit(f"paper_experiment: {cache} not found; run without --from-results first")
        results = json.loads(cache.read_text())
        args.ablation_sets = results["ablation_sets"]
    else:
        for tool in ("edacrt", "edacrt_paper_rays"):
            if not (args.build / tool).exists():
                sys.exit(f"paper_experiment: {args.build / tool} not found; build it with "
                         f"nice cmake --build build --target edacrt edacrt_paper_rays")
        results = measure(args, json.loads(cache.read_text()) if cache.exists() else None)
        cache.write_text(json.dumps(results, indent=1))

    figures = args.out if args.quick else ROOT / "bench" / "figures"
    figures.mkdir(parents=True, exist_ok=True)
    figure = figures / "paper_speedup.png"
    plot(results, figure)
    section = markdown(args, results, figure)
    (args.out / "paper_experiment.md").write_text(section)
    if args.readme:
        splice(ROOT / "bench" / "README.md", HEADING, section)
    print(f"wrote {args.out / 'paper_experiment.md'}, {figure}"
          f"{' and bench/README.md' if args.readme else ''}")


if __name__ == "__main__":
    main()
