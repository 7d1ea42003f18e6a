#!/usr/bin/python3
"""The headline `edacrt bench` run: every method per frame (set_scene + trace) on camera,
diffuse, AO and shadow rays of the four large scenes at 1024x1024, 2 threads with the 1-thread
sweep. Keeps the JSON and markdown in bench/results/ and puts the table into bench/README.md.

  bench/bench_run.py --readme      (about 25 minutes on 2 cores)
  bench/bench_run.py --quick       (bunny, 128x128, one frame: checks that it works)
"""
import argparse
import functools
import json
import sys
import time
from pathlib import Path

from bench_common import ROOT, run as run_checked
from readme_section import generated_line, splice

HEADING = "## edacrt bench, measured"
run = functools.partial(run_checked, tool="bench_run")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--build", type=Path, default=ROOT / "build")
    parser.add_argument("--quick", action="store_true", help="bunny, 128x128, one frame")
    parser.add_argument("--readme", action="store_true",
                        help="put the section into bench/README.md under its heading")
    args = parser.parse_args()
    command = "bench/bench_run.py " + " ".join(sys.argv[1:])
    out = ROOT / "out" / "bench_run" if args.quick else ROOT / "bench" / "results"
    out.mkdir(parents=True, exist_ok=True)
    stem = out / f"edacrt_bench_{time.strftime('%Y-%m-%d')}"
    scenes = ["bunny"] if args.quick else ["bunny", "sponza", "sibenik", "conference"]
    size = "128" if args.quick else "1024"
    flags = [a for s in scenes for a in ("--scene", s)] + [
        "--sets", "camera,diffuse,ao,shadow", "--spp", "1", "--width", size, "--height", size,
        "--repeat", "1" if args.quick else "5", "--thread-sweep", "--threads", "2"]
    started = time.time()
    run([args.build / "edacrt", "bench", *flags, "--json", stem.with_suffix(".json"),
         "--markdown", stem.with_suffix(".md"), "-q"])
    results = json.loads(stem.with_suffix(".json").read_text())
    link = (f"results/{stem.name}" if not args.quick else str(stem))
    section = "\n".join([
        HEADING, "",
        generated_line(command, results["machine"], time.time() - started), "",
        "It runs `build/edacrt bench " + " ".join(flags) + "` and keeps the output in "
        f"[{stem.name}.json]({link}.json) and [{stem.name}.md]({link}.md). Every method "
        f"found the same hits: {'yes' if results['agreement_ok'] else 'NO'}. `x embree`: frame "
        "time over Embree's in its fastest mode; `1t/Nt`: frame time on 1 thread over 2.", "",
        *stem.with_suffix(".md").read_text().split("\n")[2:], ""])
    if args.readme:
        splice(ROOT / "bench" / "README.md", HEADING, section)
    print(section)


if __name__ == "__main__":
    main()
