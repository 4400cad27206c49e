#!/usr/bin/env python3
"""Compares the per-stage times of two caustics-render builds under the same load.

Runs `caustics-render --timings --frames F` of build A and build B alternately, R
rounds each (A, B, A, B, ...), parses their tables and prints per stage the median
over the rounds of each run's median (wall-clock CPU column: the CLI's timings are
synchronous, so a stage's CPU time is its wall time), and B/A; with --cpu also each
build's process CPU time per frame after the first (from a second run of one frame),
a figure the machine's load stretches far less. Extra arguments go to
both renders (e.g. --size 256 or a scene). Under load, read the ratios. Then it
compares the two builds' last images (PREFIX.exr, every layer): the largest absolute
difference per layer and the relative L2 of the final colour (needs OpenImageIO's
Python module, as /usr/bin/python3 has). scripts/compare-builds.py does the same
for caustics-bench's configurations and their errors.

  /usr/bin/python3 scripts/frame-ab.py /work/main/build/bin/caustics-render \
      build/bin/caustics-render --rounds 3 --frames 5
"""
import argparse
import os
import re
import resource
import statistics
import subprocess
import sys
import tempfile


def children_cpu():
    usage = resource.getrusage(resource.RUSAGE_CHILDREN)
    return usage.ru_utime + usage.ru_stime


def run(binary, frames, extra, prefix):
    """The run's timing table, with its process's CPU seconds as "process cpu (s)"."""
    start = children_cpu()
    out = subprocess.run([binary, "--timings", "--frames", str(frames), "--output", prefix] + extra,
                         stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    if out.returncode != 0:
        sys.exit(f"{binary} failed ({out.returncode}):\n{out.stdout[-2000:]}")
    table, stages = False, {}
    for line in out.stdout.splitlines():
        if line.startswith("per-stage time"):
            table = True
            continue
        m = re.match(r"^\s{2}(\S.*?)\s{2,}(\S+)\s+(\S+)\s*$", line) if table else None
        if m and m.group(1) != "stage":
            stages[m.group(1)] = float(m.group(3))
    if not stages:
        sys.exit(f"{binary}: no timing table in its output:\n{out.stdout[-2000:]}")
    stages["process cpu (s)"] = children_cpu() - start
    return stages


def alternate(args, extra, tmp):
    """Runs A, B, A, B, ...; returns each build's timing tables, one per round."""
    runs = {"a": [], "b": []}
    for r in range(args.rounds):
        for key in ("a", "b"):
            table = run(getattr(args, key), args.frames, extra, os.path.join(tmp, key))
            if args.cpu:
                # CPU time of the frames after the first (the same process with one
                # frame less): llvmpipe's work, which the load stretches far less than
                # the wall time.
                one = run(getattr(args, key), 1, extra, os.path.join(tmp, key + "1"))
                table["cpu per later frame (ms)"] = (
                    1000.0 * (table["process cpu (s)"] - one["process cpu (s)"]) / (args.frames - 1))
            runs[key].append(table)
            wall = table.get("whole frame (wall clock)", float("nan"))
            print(f"round {r + 1}: {key.upper()} whole frame {wall:.1f} ms", flush=True)
    return runs


def print_table(args, runs):
    order = list(runs["a"][0]) + [s for s in runs["b"][0] if s not in runs["a"][0]]
    width = max(len(s) for s in order)
    print(f"median over {args.rounds} rounds of each run's median of {args.frames} frames "
          f"(ms, wall):\n  {'stage':<{width}}  {'A':>9}  {'B':>9}  {'B/A':>6}")
    for stage in order:
        med = {}
        for key in ("a", "b"):
            values = [r[stage] for r in runs[key] if stage in r]
            med[key] = statistics.median(values) if values else None
        fmt = lambda v: f"{v:9.1f}" if v is not None else f"{'-':>9}"
        ratio = (f"{med['b'] / med['a']:6.2f}" if med["a"] and med["b"] is not None
                 else f"{'-':>6}")
        print(f"  {stage:<{width}}  {fmt(med['a'])}  {fmt(med['b'])}  {ratio}")


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("a")
    parser.add_argument("b")
    parser.add_argument("--rounds", type=int, default=3)
    parser.add_argument("--frames", type=int, default=5)
    parser.add_argument("--cpu", action="store_true",
                        help="also run each build with one frame: CPU ms per later frame")
    args, extra = parser.parse_known_args()
    with tempfile.TemporaryDirectory() as tmp:
        print_table(args, alternate(args, extra, tmp))
        compare_images(os.path.join(tmp, "a.exr"), os.path.join(tmp, "b.exr"))


def compare_images(a, b):
    try:
        import numpy
        import OpenImageIO
    except ImportError:
        print("images not compared: no OpenImageIO Python module (use /usr/bin/python3)")
        return
    def load(path):
        image = OpenImageIO.ImageInput.open(path)
        names, pixels = list(image.spec().channelnames), image.read_image(format="float")
        image.close()
        return names, numpy.asarray(pixels, dtype=numpy.float64)
    (names_a, pixels_a), (names_b, pixels_b) = load(a), load(b)
    if names_a != names_b or pixels_a.shape != pixels_b.shape:
        print(f"images differ in layout: {names_a} {pixels_a.shape} / {names_b} {pixels_b.shape}")
        return
    print("last images, B against A: largest absolute difference per layer (largest value)")
    for k, name in enumerate(names_a):
        difference = numpy.abs(pixels_b[..., k] - pixels_a[..., k]).max()
        print(f"  {name:<12} {difference:.3g} ({numpy.abs(pixels_a[..., k]).max():.3g})")
    rgb = [names_a.index(c) for c in ("R", "G", "B") if c in names_a]
    if rgb:
        d, n = pixels_b[..., rgb] - pixels_a[..., rgb], pixels_a[..., rgb]
        print(f"  final colour relative L2: {numpy.sqrt((d * d).sum() / max((n * n).sum(), 1e-300)):.3g}")


if __name__ == "__main__":
    main()
