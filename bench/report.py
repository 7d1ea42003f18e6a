#!/usr/bin/python3
"""Speed against error: renders every bundled scene with every method until a time budget,
measuring the error against a cached high-spp reference after every pass; measures the hit
accuracy of every method against a double-precision reference; times the seed report's
480x270 comparison. Writes bench/figures/*.png and bench/README.md.

Run from the repository root after scripts/setup:  bench/report.py [--quick]
Uses Debian's /usr/bin/python3 with python3-matplotlib (installed by scripts/setup).
"""
import argparse
import json
import statistics
import subprocess
import sys
import time
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from bench_common import ROOT, scene_list  # noqa: E402
from readme_section import README, generated_line  # noqa: E402

METHODS = ["edacrt", "dacrt", "bvh", "embree", "naive"]
COLOURS = {"edacrt": "tab:red", "dacrt": "tab:orange", "bvh": "tab:blue",
           "embree": "tab:green", "naive": "tab:gray"}
# name, scene, extra render flags: the list "report" of assets/scenes.json, bundled scenes
SCENES = [(s.name, str(Path("assets") / s.relative), []) for s in scene_list("report")]


def edacrt(build, *args, capture=True):
    command = [str(build / "edacrt"), *map(str, args)]
    result = subprocess.run(command, cwd=ROOT, capture_output=capture, text=True)
    if result.returncode != 0:
        sys.exit(f"report: {' '.join(command)} failed:\n{result.stdout}{result.stderr}")
    return result.stdout


def render_settings(args):
    return ["--width", args.size, "--height", args.size, "--integrator", "path"]


def reference(build, out, name, scene, flags, args):
    """The cached reference image of a scene: Embree (fastest), a seed no other run uses."""
    path = out / f"reference_{name}_{args.size}_{args.reference_spp}.pfm"
    if not path.exists():
        print(f"reference {name}: {args.reference_spp} spp (cached as {path})", flush=True)
        edacrt(build, "render", "--scene", scene, "--method", "embree", "--seed", 987654,
               "--spp", args.reference_spp, *render_settings(args), *flags, "--out", path)
    return path


def convergence(build, out, name, scene, flags, ref, args):
    """Error after every pass, per method: [(seconds, rmse, relative mse, spp)]."""
    curves = {}
    for method in METHODS:
        stats = out / f"convergence_{name}_{method}.json"
        edacrt(build, "render", "--scene", scene, "--method", method, "--seed", 1,
               "--time-budget", args.budget, *render_settings(args), *flags,
               "--reference", ref, "--stats", stats, "--out", out / f"{name}_{method}.png")
        passes = json.loads(stats.read_text())["passes"]
        curves[method] = [(p["seconds"], p["rmse"], p["relative_mse"], p["spp"]) for p in passes]
        last = curves[method][-1]
        print(f"  {name} {method}: {last[3]} spp in {last[0]:.2f} s, rmse {last[1]:.4g}",
              flush=True)
    return curves


def plot_convergence(figures, name, curves, args):
    fig, ax = plt.subplots(figsize=(6, 4.2), dpi=110)
    for method, points in curves.items():
        ax.loglog([p[0] for p in points], [p[1] for p in points], "-o", markersize=2.5,
                  color=COLOURS[method], label=method)
    ax.set_xlabel("render time (s)")
    ax.set_ylabel("RMSE against the reference")
    ax.set_title(f"{name}: path tracing {args.size}x{args.size}, error against time")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    fig.tight_layout()
    path = figures / f"convergence_{name}.png"
    fig.savefig(path)
    plt.close(fig)
    return path


def accuracy(build, out, name, scene, args):
    stats = out / f"accuracy_{name}.json"
    edacrt(build, "accuracy", "--scene", scene, "--rays", args.accuracy_rays, "--stats", stats)
    return json.loads(stats.read_text())["results"]


def plot_accuracy(figures, results_by_scene):
    fig, axes = plt.subplots(1, len(results_by_scene), figsize=(5 * len(results_by_scene), 4),
                             dpi=110, squeeze=False)
    markers = {"camera": "o", "random inside": "s", "from surfaces": "^",
               "grazing from surfaces": "v", "axis-parallel": "D"}
    for ax, (name, results) in zip(axes[0], results_by_scene.items()):
        for r in results:
            ax.loglog(r["mrays_per_second"], max(r["mean_relative_t_error"], 1e-12),
                      markers[r["ray_set"]], color=COLOURS[r["method"]], markersize=5)
        ax.set_title(name)
        ax.set_xlabel("Mrays/s (closest hit)")
        ax.set_ylabel("mean relative |t| error vs double")
        ax.grid(True, which="both", alpha=0.3)
    handles = [plt.Line2D([], [], color=c, marker="o", linestyle="", label=m)
               for m, c in COLOURS.items()]
    handles += [plt.Line2D([], [], color="k", marker=mk, linestyle="", label=s)
                for s, mk in markers.items()]
    fig.legend(handles=handles, loc="lower center", ncol=5, fontsize=8)
    fig.tight_layout(rect=(0, 0.14, 1, 1))
    path = figures / "accuracy.png"
    fig.savefig(path)
    plt.close(fig)
    return path


def seed_comparison(build, out, args):
    """The seed report's experiment: 480x270 primary rays at 4 and 8 spp, every method."""
    rows = []
    for label, scene in [("sphere, 1,280 triangles", "builtin:sphere:subdiv=3"),
                         ("spot, 5,856 triangles", "assets/spot/spot.obj")]:
        for spp in (4, 8):
            row = {"scene": label, "spp": spp, "rays": 480 * 270 * spp}
            for method in METHODS:
                times = []
                for _ in range(1 if method == "naive" else args.repeats):
                    stats = out / "seed.json"
                    edacrt(build, "render", "--scene", scene, "--method", method, "--integrator",
                           "primary", "--width", 480, "--height", 270, "--spp", spp, "--stats",
                           stats, "--out", out / "seed.png")
                    times.append(json.loads(stats.read_text())["trace_seconds"])
                row[method] = statistics.median(times)
            print(f"  seed table {label} {spp} spp: " +
                  ", ".join(f"{m} {row[m]:.3f} s" for m in METHODS), flush=True)
            rows.append(row)
    return rows


# Headings of the sections that other scripts append to bench/README.md, after this report's.
# The sections this report writes, at the top of bench/README.md; the other scripts' follow.
OWN_SECTIONS = ["## Error against time (path tracing)", "## Hit accuracy against speed",
                "## The seed report's comparison, with every method"]


def markdown_report(args, curves_by_scene, figures, accuracy_by_scene, seed_rows, started):
    lines = [
        "# Speed against error",
        "",
        generated_line(f"bench/report.py{' --quick' if args.quick else ''}",
                       seconds=time.time() - started),
        "",
        "Every method is exact, so at equal samples per pixel "
        "the images agree; the curves show what each method's speed buys. Timings are of one "
        "shared, noisy machine: read ratios between methods of the same run, not absolutes.",
        "",
        "## Error against time (path tracing)",
        "",
        f"Each scene at {args.size}x{args.size}, path tracing (NEE + MIS, Russian roulette, max "
        f"depth 8), rendered progressively for {args.budget} s per method; after every pass the "
        f"RMSE against a {args.reference_spp}-spp reference (Embree, another seed, cached in "
        "`out/bench/`). Render time includes shading, which every method shares.",
        "",
    ]
    for name, path in figures["convergence"].items():
        lines += [f"![{name}](figures/{path.name})", ""]
    lines += ["| scene | method | spp in budget | final RMSE | final relMSE | trace share |",
              "|---|---|---:|---:|---:|---:|"]
    for name, curves in curves_by_scene.items():
        for method, points in curves.items():
            seconds, rmse, relmse, spp = points[-1]
            stats = json.loads((args.out / f"convergence_{name}_{method}.json").read_text())
            share = stats["trace_seconds"] / max(stats["render_seconds"], 1e-9)
            lines.append(f"| {name} | {method} | {spp} | {rmse:.4g} | {relmse:.4g} | "
                         f"{100 * share:.0f}% |")
    lines += [
        "",
        "## Hit accuracy against speed",
        "",
        f"`edacrt accuracy`: {args.accuracy_rays} rays per set, closest hit, compared with a "
        "double-precision brute-force reference. *hit diff*: hit/miss differs; *tri diff*: "
        "another triangle, not at the same distance (ties on shared edges are not counted); "
        "relative |t| error over the rays where both hit the same surface. The reference "
        "treats a t within double rounding of 0 (2^-40 of the coordinates) as no hit. Rays from surfaces are spawned as the renderer "
        "spawns them (offset past the hit point's error bound); grazing ones leave at 1e-6 to "
        "1e-1 rad. Mrays/s are for batches of this size (small for the divide-and-conquer "
        "methods).",
        "",
        f"![accuracy](figures/{figures['accuracy'].name})",
        "",
        "| scene | method | ray set | Mrays/s | hit diff | tri diff | max rel t | mean rel t |",
        "|---|---|---|---:|---:|---:|---:|---:|",
    ]
    for name, results in accuracy_by_scene.items():
        for r in results:
            lines.append(
                f"| {name} | {r['method']} | {r['ray_set']} | {r['mrays_per_second']:.3g} | "
                f"{r['hit_mismatch_fraction']:.2g} | {r['triangle_mismatch_fraction']:.2g} | "
                f"{r['max_relative_t_error']:.2g} | {r['mean_relative_t_error']:.2g} |")
    lines += [
        "",
        "## The seed report's comparison, with every method",
        "",
        "The report that started the project traced 480x270 images at 4 and 8 rays per pixel: "
        "naive 33 s and 57 s, EDACRT 17 s and 26 s (1,200 triangles). The same experiment "
        "(primary rays, trace time only, median of "
        f"{args.repeats} runs, naive once):",
        "",
        "| scene | spp | rays | " + " | ".join(METHODS) + " |",
        "|---|---:|---:|" + "---:|" * len(METHODS),
    ]
    for row in seed_rows:
        lines.append(f"| {row['scene']} | {row['spp']} | {row['rays']:,} | " +
                     " | ".join(f"{row[m]:.3f} s" for m in METHODS) + " |")
    lines += ["", "Reproduce: `scripts/setup && bench/report.py` (about ten minutes; "
              "`--quick` for a smoke run).", ""]
    return "\n".join(lines)


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--out", type=Path, default=ROOT / "out" / "bench")
    parser.add_argument("--quick", action="store_true", help="tiny budgets, to check it runs")
    parser.add_argument("--only", choices=["convergence", "accuracy", "seed"], action="append",
                        help="re-measure only these sections (others come from out/bench)")
    args = parser.parse_args()
    args.size, args.budget, args.reference_spp = (64, 1.0, 64) if args.quick else (256, 15.0, 2048)
    args.accuracy_rays, args.repeats = (2000, 1) if args.quick else (40000, 3)
    if not (args.build / "edacrt").exists():
        sys.exit(f"report: {args.build / 'edacrt'} not found; run scripts/setup first")
    args.out.mkdir(parents=True, exist_ok=True)
    figures_dir = args.out / "figures" if args.quick else ROOT / "bench" / "figures"
    figures_dir.mkdir(parents=True, exist_ok=True)
    started = time.time()

    def section(key, measure):
        """Measures a section, or reuses its cached results when --only names others."""
        cache = args.out / f"results_{key}.json"
        if args.only and key not in args.only and cache.exists():
            return json.loads(cache.read_text())
        results = measure()
        cache.write_text(json.dumps(results))
        return results

    def measure_convergence():
        curves = {}
        for name, scene, flags in SCENES:
            ref = reference(args.build, args.out, name, scene, flags, args)
            curves[name] = convergence(args.build, args.out, name, scene, flags, ref, args)
        return curves

    def measure_accuracy():
        results = {}
        for name, scene, _ in SCENES:
            print(f"accuracy {name}", flush=True)
            results[name] = accuracy(args.build, args.out, name, scene, args)
        return results

    curves_by_scene = section("convergence", measure_convergence)
    figures = {"convergence": {name: plot_convergence(figures_dir, name, curves, args)
                               for name, curves in curves_by_scene.items()}}
    accuracy_by_scene = section("accuracy", measure_accuracy)
    figures["accuracy"] = plot_accuracy(figures_dir, accuracy_by_scene)
    print("seed comparison", flush=True)
    seed_rows = section("seed", lambda: seed_comparison(args.build, args.out, args))

    report = markdown_report(args, curves_by_scene, figures, accuracy_by_scene, seed_rows, started)
    readme = README
    # The sections from the first that is not this report's (other scripts', hand-written
    # ones) are kept.
    old = (readme.read_text() if readme.exists() else "").splitlines(keepends=True)
    kept = next((i for i, line in enumerate(old)
                 if line.startswith("## ") and line.rstrip("\n") not in OWN_SECTIONS), len(old))
    readme.write_text(report.rstrip() + "\n" + ("\n" + "".join(old[kept:]) if kept < len(old)
                                                else ""))
    print(f"wrote {readme} and {len(figures['convergence']) + 1} figures "
          f"in {time.time() - started:.0f} s")


if __name__ == "__main__":
    main()
