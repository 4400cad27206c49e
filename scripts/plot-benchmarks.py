#!/usr/bin/env python3
"""Plots caustics-bench results: run time against relative L2 error, one panel per scene.

    plot-benchmarks.py RESULTS/benchmarks.csv [--output benchmarks.png]
    plot-benchmarks.py --check RESULTS/benchmarks.csv

Each technique is one colour: its Pareto front (the configurations that no cheaper
configuration of the same technique beats in error) is a line, the dominated
configurations are faint markers. The CPU reference at its photon counts is drawn the
same way, and the front over every technique and the reference is the thick grey
line. x: wall time per frame (reference: per render), ms, log; y: relative L2 error of
the caustic irradiance against the high-photon-count reference, log.

--check validates a CSV instead (CI's smoke test): the expected columns, finite
numbers where a number is expected, and the "none" technique scoring exactly what a
renderer without caustic light must. Needs only the standard library; the plot needs
matplotlib (exit code 3 without it, so that caustics-bench can say the plot was
skipped).
"""
import argparse
import csv
import math
import sys

COLUMNS = ["scene", "technique", "knobs", "width", "height", "frames", "wall_ms", "gpu_ms",
           "rel_l2", "flux_ratio", "peak_error_px", "psnr_db", "rmse", "nonfinite_px",
           "compared_px", "status"]
# Columns that must hold a finite number in every row ("gpu_ms" only for GPU techniques:
# the reference runs on the CPU and leaves it empty).
FINITE = ["width", "height", "frames", "wall_ms", "rel_l2", "flux_ratio", "peak_error_px",
          "psnr_db", "rmse", "nonfinite_px", "compared_px"]
STAGE_COLUMNS = ["scene", "technique", "knobs", "stage", "gpu_ms", "cpu_ms"]


def read_rows(path):
    with open(path, newline="") as f:
        reader = csv.DictReader(f)
        return reader.fieldnames or [], list(reader)


def finite(text):
    try:
        return math.isfinite(float(text))
    except ValueError:
        return False


def check(path):
    """Returns a list of problems with the CSV at path (empty when it is valid)."""
    problems = []
    columns, rows = read_rows(path)
    if columns != COLUMNS:
        return [f"{path}: columns {columns}, expected {COLUMNS}"]
    if not rows:
        return [f"{path}: no rows"]
    techniques = set()
    for number, row in enumerate(rows, start=2):
        where = f"{path}:{number} ({row['scene']}, {row['technique']}, {row['knobs']})"
        techniques.add(row["technique"])
        if row["status"] != "ok":
            problems.append(f"{where}: status '{row['status']}'")
        names = FINITE + ([] if row["technique"] == "reference" else ["gpu_ms"])
        for name in names:
            if not finite(row[name]):
                problems.append(f"{where}: {name} = '{row[name]}' is not a finite number")
        if row["technique"] == "reference" and row["gpu_ms"] != "":
            problems.append(f"{where}: the CPU reference has a GPU time '{row['gpu_ms']}'")
        if finite(row["wall_ms"]) and float(row["wall_ms"]) <= 0:
            problems.append(f"{where}: wall_ms = {row['wall_ms']} is not positive")
        if finite(row["compared_px"]) and float(row["compared_px"]) <= 0:
            problems.append(f"{where}: no receiver pixel was compared")
        if row["technique"] == "none" and finite(row["rel_l2"]) and finite(row["flux_ratio"]):
            # "none" adds no caustic light: its caustic irradiance is 0, so ||0 - r|| / ||r||
            # is 1 and the flux ratio 0, up to the rounding of a double sum over < 1e6 pixels
            # and the 6 significant digits written (1e-5 covers both).
            if abs(float(row["rel_l2"]) - 1.0) > 1e-5 or abs(float(row["flux_ratio"])) > 1e-5:
                problems.append(f"{where}: 'none' must score rel_l2 = 1 and flux_ratio = 0, got "
                                f"{row['rel_l2']} and {row['flux_ratio']}")
    if "reference" not in techniques:
        problems.append(f"{path}: no reference rows (the reference ladder)")
    stages_path = path[: -len("benchmarks.csv")] + "benchmark-stages.csv"
    if path.endswith("benchmarks.csv"):
        stage_columns, stages = read_rows(stages_path)
        if stage_columns != STAGE_COLUMNS:
            problems.append(f"{stages_path}: columns {stage_columns}, expected {STAGE_COLUMNS}")
        else:
            keyed = {(s["scene"], s["technique"], s["knobs"]) for s in stages}
            for row in rows:
                if (row["scene"], row["technique"], row["knobs"]) not in keyed:
                    problems.append(f"{stages_path}: no stages for {row['scene']}, "
                                    f"{row['technique']}, {row['knobs']}")
            for stage in stages:
                # Empty gpu_ms: a CPU-only stage (the reference's, or e.g. the scene
                # snapshot); a GPU stage whose query failed makes the row's total
                # gpu_ms non-finite, which the row check above reports.
                if not finite(stage["cpu_ms"]) or (stage["gpu_ms"] != "" and
                                                   not finite(stage["gpu_ms"])):
                    problems.append(f"{stages_path}: stage '{stage['stage']}' of "
                                    f"{stage['technique']} {stage['knobs']} has a time that is "
                                    f"not a finite number")
    return problems


def pareto_front(points):
    """The points (time, error, label) that no cheaper point beats in error, by time."""
    front = []
    for point in sorted(points):
        if not front or point[1] < front[-1][1]:
            front.append(point)
    return front


def photons_label(knobs):
    """"photons=9998243" as "1.0e7 photons"."""
    mantissa, exponent = f"{float(knobs.split('=')[-1]):.1e}".split("e")
    return f"{mantissa}e{int(exponent)} photons"


def plot(path, output):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        print("plot-benchmarks: matplotlib is not installed (apt install python3-matplotlib)",
              file=sys.stderr)
        return 3
    _, rows = read_rows(path)
    scenes = list(dict.fromkeys(row["scene"] for row in rows))
    techniques = list(dict.fromkeys(row["technique"] for row in rows))
    if not scenes:
        print(f"plot-benchmarks: {path} has no rows", file=sys.stderr)
        return 1
    columns = 2 if len(scenes) > 1 else 1
    lines = (len(scenes) + columns - 1) // columns
    figure, axes = plt.subplots(lines, columns, figsize=(5.0 * columns, 3.9 * lines),
                                squeeze=False)
    colours = {name: plt.cm.tab10(i % 10) for i, name in enumerate(techniques)}
    for panel, scene in zip(axes.flat, scenes):
        everything = []
        for technique in techniques:
            points = [(float(r["wall_ms"]), float(r["rel_l2"]), r["knobs"]) for r in rows
                      if r["scene"] == scene and r["technique"] == technique
                      and finite(r["wall_ms"]) and finite(r["rel_l2"])
                      and float(r["wall_ms"]) > 0 and float(r["rel_l2"]) > 0]
            if not points:
                continue
            everything += points
            front = pareto_front(points)
            label = "CPU reference (photons)" if technique == "reference" else technique
            style = "s--" if technique == "reference" else "o-"
            panel.plot([p[0] for p in front], [p[1] for p in front], style,
                       color=colours[technique], label=label, markersize=4, linewidth=1.2)
            dominated = [p for p in points if p not in front]
            panel.plot([p[0] for p in dominated], [p[1] for p in dominated], "o",
                       color=colours[technique], alpha=0.3, markersize=3)
            for p in front:
                text = photons_label(p[2]) if technique == "reference" else p[2]
                panel.annotate(text, (p[0], p[1]), fontsize=5.5, xytext=(3, 3),
                               textcoords="offset points", color=colours[technique])
        overall = pareto_front(everything)
        panel.plot([p[0] for p in overall], [p[1] for p in overall], "-", color="grey",
                   alpha=0.35, linewidth=5, zorder=0, label="Pareto front (all)")
        panel.set_xscale("log")
        panel.set_yscale("log")
        panel.set_title(scene, fontsize=10)
        panel.set_xlabel("wall time per frame / render (ms)", fontsize=8)
        panel.set_ylabel("relative L2 error, caustic irradiance", fontsize=8)
        panel.tick_params(labelsize=7)
        panel.grid(True, which="both", alpha=0.2)
        panel.legend(fontsize=6.5, loc="lower left")
    for panel in list(axes.flat)[len(scenes):]:
        panel.axis("off")
    width, height = rows[0]["width"], rows[0]["height"]
    figure.suptitle(f"caustics-bench: time against error, {width} x {height} pixels",
                    fontsize=11)
    figure.tight_layout()
    figure.savefig(output, dpi=90)
    print(f"plot-benchmarks: wrote {output}")
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="benchmarks.csv written by caustics-bench")
    parser.add_argument("--output", default="benchmarks.png", help="PNG to write")
    parser.add_argument("--check", action="store_true",
                        help="validate the CSV (columns, finite numbers) instead of plotting")
    arguments = parser.parse_args()
    try:
        if arguments.check:
            problems = check(arguments.csv)
            for problem in problems:
                print(f"plot-benchmarks: {problem}", file=sys.stderr)
            if not problems:
                print(f"plot-benchmarks: {arguments.csv} is valid")
            return 1 if problems else 0
        return plot(arguments.csv, arguments.output)
    except (OSError, KeyError, ValueError) as error:
        print(f"plot-benchmarks: cannot read {arguments.csv}: {error}", file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main())
