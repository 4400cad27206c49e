#!/usr/bin/env python3
"""Compares two builds of the module with caustics-bench, in one run.

Runs BEFORE/bin/caustics-bench and AFTER/bin/caustics-bench alternately (round
after round, so that machine load drifts hit both alike) on the same scenes with
the same ground truth (one shared reference cache), then prints, per
configuration, the relative L2 error and flux ratio of both builds (equal to 3
significant digits or flagged) and the median ratio of frame wall times.

  xvfb-run -a scripts/compare-builds.py BEFORE_BUILD AFTER_BUILD \
      [--scenes ball-lens,pool] [--techniques screen-space,caustic-maps] [--rounds 3]

A refactoring that should not change behaviour must print no 'DIFFERS' row; the
wall-time ratio says whether it costs time (measure on a quiet machine). Exits 1
when an error figure differs. Output and bench results go to --output.
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys


def run_bench(build, scenes, techniques, output, cache, frames, extra):
    command = [os.path.join(build, "bin", "caustics-bench"), "--scenes", scenes,
               "--output", output, "--no-plot", "--frames", str(frames),
               "--reference-ladder", "1e5", "--reference-repeats", "1"]
    if techniques:
        command += ["--techniques", techniques]
    command += extra
    environment = dict(os.environ, CAUSTICS_REFERENCE_CACHE=cache)
    print("compare-builds: " + " ".join(command), flush=True)
    subprocess.run(command, check=True, env=environment, stdout=subprocess.DEVNULL)
    with open(os.path.join(output, "benchmarks.csv"), newline="") as f:
        return {(r["scene"], r["technique"], r["knobs"]): r for r in csv.DictReader(f)}


def same3(a, b):
    if a == b:
        return True
    try:
        x, y = float(a), float(b)
    except ValueError:
        return False
    return f"{x:.3g}" == f"{y:.3g}"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("before")
    parser.add_argument("after")
    parser.add_argument("--scenes", default="ball-lens,pool")
    parser.add_argument("--techniques", default="")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--output", default="compare-builds")
    # Anything else is passed on to caustics-bench (e.g. --reference-photons 2e6).
    args, bench_args = parser.parse_known_args()
    args.bench_args = [a for a in bench_args if a != "--"]

    cache = os.path.abspath(os.path.join(args.output, "reference-cache"))
    os.makedirs(cache, exist_ok=True)
    results = {"before": [], "after": []}
    for round_index in range(args.rounds):
        for name in ("before", "after"):
            build = getattr(args, name)
            output = os.path.join(args.output, f"{name}-{round_index}")
            results[name].append(run_bench(build, args.scenes, args.techniques, output, cache,
                                           args.frames, args.bench_args))

    differs = 0
    print(f"\n{'scene':10} {'technique':13} {'knobs':42} {'relL2 before':>12} {'after':>9} "
          f"{'flux before':>11} {'after':>7} {'wall after/before':>17}")
    for key, first in results["before"][0].items():
        if first["technique"] == "reference":
            continue
        later = results["after"][0].get(key)
        if later is None:
            print(f"{key[0]:10} {key[1]:13} {key[2]:42} missing in the after build")
            differs += 1
            continue
        ratios = [float(a[key]["wall_ms"]) / float(b[key]["wall_ms"])
                  for a, b in zip(results["after"], results["before"])
                  if key in a and float(b[key]["wall_ms"]) > 0]
        same = same3(first["rel_l2"], later["rel_l2"]) and same3(first["flux_ratio"],
                                                                later["flux_ratio"])
        differs += 0 if same else 1
        ratio = f"{statistics.median(ratios):.3f}" if ratios else "n/a"
        print(f"{key[0]:10} {key[1]:13} {key[2]:42} {float(first['rel_l2']):12.4g} "
              f"{float(later['rel_l2']):9.4g} {float(first['flux_ratio']):11.4g} "
              f"{float(later['flux_ratio']):7.4g} {ratio:>17}{'' if same else '  DIFFERS'}")
    print(f"\ncompare-builds: {differs} configuration(s) differ at 3 significant digits; "
          f"wall ratios are medians over {args.rounds} round(s)")
    return 1 if differs else 0


if __name__ == "__main__":
    sys.exit(main())
