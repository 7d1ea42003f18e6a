#!/usr/bin/python3
"""Every generated section of bench/README.md, from the code of this checkout, or (--check)
the sections whose engine/ code has changed since the revision that made them.

  bench/regenerate.py              (about three hours on 2 cores: run on a quiet machine)
  bench/regenerate.py --quick      (smoke runs into out/regenerate/README.md; bench/ untouched)
  bench/regenerate.py --only sweep --only paper   (some of them)
  bench/regenerate.py --check      (a notice per stale section; scripts/test prints it)
Each generator writes its section under its heading, beginning with the line that names its
command and revision (readme_section.generated_line).
"""
import argparse
import os
import shutil
import subprocess
import sys
import time

from bench_common import ROOT
from readme_section import MARKER, sections

README = ROOT / "bench" / "README.md"
# name: (command, headings it writes). The order is the README's.
GENERATORS = {
    "report": (["bench/report.py"],
               ["## Error against time (path tracing)", "## Hit accuracy against speed",
                "## The seed report's comparison, with every method"]),
    "paper": (["bench/paper_experiment.py", "--readme"],
              ["## EDACRT against DACRT (the paper's experiment)"]),
    "sweep": (["bench/sweep.py", "--readme"], ["## Each method at its best: the switch sweep"]),
    "deviations": (["bench/deviations.py", "--readme"], ["## Deviations from the paper, measured"]),
    "bvh": (["bench/bvh_baseline.py", "--readme"], ["## BVH baseline"]),
    "bench": (["bench/bench_run.py", "--readme"], ["## edacrt bench, measured"]),
    "dynamic": (["bench/dynamic.py", "--readme"], ["## Dynamic scenes"]),
    "render": (["bench/render_bench.py", "--readme"], ["## The render, against Embree"]),
    # Last: it reads the sections above.
    "targets": (["bench/targets.py", "--readme"], ["## Issue 26's targets, measured"]),
}


def git(*args):
    result = subprocess.run(["git", *args], cwd=ROOT, capture_output=True, text=True)
    return result.returncode, result.stdout.strip()


def section_revisions(text):
    """{heading: recorded revision or None} for the generators' headings in `text`: the marker
    inside the section; for report.py's sections, the one above them (it names its revision
    once, under the title)."""
    found_sections = sections(text)

    def marked(lines):
        return next((m.group(1) for line in lines if (m := MARKER.search(line))), None)

    found = {}
    for name, (_, headings) in GENERATORS.items():
        shared = marked(found_sections[""]) if name == "report" else None
        for heading in headings:
            if heading in found_sections:
                found[heading] = marked(found_sections[heading]) or shared
    return found


def check():
    """Prints the stale sections; always succeeds (a notice, not a failure)."""
    if not README.exists():
        return
    stale = []
    for heading, revision in section_revisions(README.read_text()).items():
        if revision is None:
            stale.append(f"{heading[3:]}: names no revision")
            continue
        base = revision.removesuffix("+changes")
        code, _ = git("cat-file", "-e", base + "^{commit}")
        if code != 0:
            stale.append(f"{heading[3:]}: revision {base} is not in this clone")
            continue
        code, changed = git("diff", "--stat", "--format=", base, "HEAD", "--", "engine")
        if changed:
            files = len([l for l in changed.splitlines() if "|" in l])
            stale.append(f"{heading[3:]}: {files} engine/ file(s) changed since {revision}")
    if stale:
        print("notice: bench/README.md sections measured on older engine code "
              "(bench/regenerate.py --only NAME remakes one):")
        for line in stale:
            print(f"  {line}")
    else:
        print("bench/README.md: every generated section is from the current engine code")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--quick", action="store_true",
                        help="smoke runs, into out/regenerate/README.md")
    parser.add_argument("--only", action="append", choices=list(GENERATORS),
                        help="this generator only (repeatable)")
    parser.add_argument("--check", action="store_true",
                        help="list the sections whose engine/ code changed since they were made")
    args = parser.parse_args()
    if args.check:
        check()
        return
    env = dict(os.environ)
    if args.quick:
        target = ROOT / "out" / "regenerate" / "README.md"
        target.parent.mkdir(parents=True, exist_ok=True)
        shutil.copy(README, target)
        env["EDACRT_BENCH_README"] = str(target)
    for name in args.only or GENERATORS:
        command = GENERATORS[name][0] + (["--quick"] if args.quick else [])
        print(f"regenerate: {' '.join(command)}", file=sys.stderr, flush=True)
        started = time.time()
        result = subprocess.run(["/usr/bin/python3", *command], cwd=ROOT, env=env,
                                stdout=subprocess.DEVNULL)
        if result.returncode != 0:
            sys.exit(f"regenerate: {' '.join(command)} failed")
        print(f"regenerate: {name} took {time.time() - started:.0f} s", file=sys.stderr)
    print(f"regenerate: wrote {env.get('EDACRT_BENCH_README', README)}", file=sys.stderr)


if __name__ == "__main__":
    main()
