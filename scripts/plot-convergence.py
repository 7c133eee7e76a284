#!/usr/bin/python3
"""Error against run time from `mvcl-bench convergence` CSVs: one PNG per scene, log-log,
relMSE (left) and RMSE (right), uniform / progressive / adaptive as the mean over seeds with a
min-max band across seeds. The reference's own error estimate is the dotted grey floor, and
uniform's final relMSE the dashed line that the bench's "R" is measured at. The sessions' own
estimate of relMSE (no reference) is drawn thin and dashed in each method's colour.

    scripts/plot-convergence.py out/convergence-*.csv -o docs/images/

It also plots what `mvcl-render --convergence-log FILE.csv` writes (any scene and lens stack,
no reference): the estimated relMSE and the mean samples per pixel against time, one PNG per
log, named after it (<log>-convergence.png).

    scripts/plot-convergence.py my-render.csv -o out/

Needs Debian's python3-matplotlib (apt-get install python3-matplotlib), hence /usr/bin/python3
rather than whatever python3 comes first on PATH.
"""
import argparse
import csv
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402

METHODS = [("uniform", "#1b6ac9"), ("progressive", "#e07b00"), ("adaptive", "#2a9d3a")]
METRICS = [("relmse", "relMSE (ε = 0.01)"), ("rmse", "RMSE")]


def curves(rows, metric):
    """{method: [(mean seconds, mean error, min error, max error)]}, point by point (uniform: its
    spp levels, the others: their passes). As in the bench's table, a run that went idle before
    the others keeps its final state, so every point averages all seeds."""
    by_method = defaultdict(lambda: defaultdict(list))  # method -> seed -> rows in step order
    for r in rows:
        if r["method"] != "reference":
            by_method[r["method"]][r["seed"]].append(r)
    result = {}
    for method, seeds in by_method.items():
        runs = [sorted(run, key=lambda r: int(r["step"])) for run in seeds.values()]
        points = []
        for k in range(max(len(run) for run in runs)):
            group = [run[min(k, len(run) - 1)] for run in runs]
            errors = [float(g[metric]) for g in group]
            seconds = sum(float(g["seconds"]) for g in group) / len(group)
            points.append((seconds, sum(errors) / len(errors), min(errors), max(errors)))
        result[method] = points
    return result


def plot_log(path, rows, out_dir):
    """A --convergence-log file: estimated relMSE (log-log) and mean spp against time."""
    points = [(float(r["seconds"]), float(r["estimated_relmse"]), float(r["mean_spp"]))
              for r in rows if r["estimated_relmse"] and float(r["seconds"]) > 0]
    if not points:
        sys.exit("plot-convergence: %s has no pass with an error estimate (every pixel needs two samples)" % path)
    fig, ax = plt.subplots(figsize=(6.5, 4.2), constrained_layout=True)
    t = [p[0] for p in points]
    ax.plot(t, [p[1] for p in points], color="#2a9d3a", marker=".", ms=3, lw=1.6, label="estimated relMSE")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time of the passes (s)")
    ax.set_ylabel("estimated relMSE (ε = 0.01)")
    ax.grid(True, which="both", alpha=0.25)
    spp = ax.twinx()
    spp.plot(t, [p[2] for p in points], color="0.5", lw=1.0, ls="--", label="mean samples per pixel")
    spp.set_ylabel("mean samples per pixel")
    lines = ax.get_legend_handles_labels()[0] + spp.get_legend_handles_labels()[0]
    ax.legend(lines, [line.get_label() for line in lines], loc="upper right", fontsize=8)
    name = os.path.splitext(os.path.basename(path))[0]
    fig.suptitle("%s: estimated error against time (%d passes)" % (name, len(rows)), fontsize=11)
    out = os.path.join(out_dir, "%s-convergence.png" % name)
    fig.savefig(out, dpi=110)
    plt.close(fig)
    return out


def plot_scene(scene, rows, out_dir):
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.4), constrained_layout=True)
    reference = [r for r in rows if r["method"] == "reference"]
    seeds = len({r["seed"] for r in rows if r["method"] == "uniform"})
    uniform_final = None
    for ax, (metric, label) in zip(axes, METRICS):
        data = curves(rows, metric)
        for method, colour in METHODS:
            points = [p for p in data.get(method, []) if p[0] > 0 and p[1] > 0]
            if not points:
                continue
            t = [p[0] for p in points]
            ax.fill_between(t, [p[2] for p in points], [p[3] for p in points], color=colour, alpha=0.2, lw=0)
            ax.plot(t, [p[1] for p in points], color=colour, lw=1.6,
                    marker="o" if method == "uniform" else ".", ms=3.5 if method == "uniform" else 3, label=method)
            if metric == "relmse" and any(r.get("estimated_relmse") for r in rows if r["method"] == method):
                estimate = [p for p in curves([r for r in rows if r.get("estimated_relmse")], "estimated_relmse")
                            .get(method, []) if p[0] > 0 and p[1] > 0]
                ax.plot([p[0] for p in estimate], [p[1] for p in estimate], color=colour, lw=0.9, ls=(0, (4, 2)),
                        label=method + ", estimated")
            if method == "uniform":
                final = points[-1][1]
                ax.axhline(final, color=colour, ls="--", lw=0.8)
                if metric == "relmse":
                    uniform_final = final
        if reference and reference[0][metric]:
            # The reference's own error: a dotted floor when it comes near the curves, else only
            # its value in the legend (a line decades below would squash the curves).
            floor = float(reference[0][metric])
            lowest = min((p[2] for points in data.values() for p in points if p[2] > 0), default=0.0)
            text = "reference's own error %.2g (%s spp)" % (floor, reference[0]["step"])
            if floor > 0.1 * lowest:
                ax.axhline(floor, color="0.45", ls=":", lw=1.0, label=text)
            else:
                ax.plot([], [], " ", label=text)
        ax.legend(loc="upper right", fontsize=8)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("wall time of the passes (s)")
        ax.set_ylabel(label)
        ax.grid(True, which="both", alpha=0.25)
    size = ""
    u = [r for r in rows if r["method"] == "uniform"]
    if u:
        size = "up to %s spp, " % max(int(r["step"]) for r in u)
    fig.suptitle("%s: error against time (%smean of %d seeds, band = min..max)" % (scene, size, seeds), fontsize=11)
    path = os.path.join(out_dir, "convergence-%s.png" % scene)
    fig.savefig(path, dpi=110)
    plt.close(fig)
    return path, uniform_final


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("csv", nargs="+", help="CSV files written by mvcl-bench convergence")
    parser.add_argument("-o", "--output", default="docs/images", help="folder for the PNGs")
    args = parser.parse_args()
    os.makedirs(args.output, exist_ok=True)
    by_scene = defaultdict(list)
    bench_files = []
    for path in args.csv:
        with open(path, newline="") as f:
            rows = list(csv.DictReader(f))
        if rows and "pass" in rows[0] and "scene" not in rows[0]:
            print("wrote", plot_log(path, rows, args.output))
        else:
            bench_files.append(path)
            for r in rows:
                by_scene[r["scene"]].append(r)
    if not by_scene and bench_files:
        sys.exit("plot-convergence: no rows in " + ", ".join(bench_files))
    for scene, rows in sorted(by_scene.items()):
        path, _ = plot_scene(scene, rows, args.output)
        print("wrote", path)


if __name__ == "__main__":
    main()
