#!/usr/bin/python3
"""Run time against error, from a CSV of apps/bench/accuracy_pareto.

  /usr/bin/python3 apps/tools/plot_pareto.py pareto_catenary.csv [more.csv ...]

writes pareto_<problem>.png next to each CSV: a log-log plot of the error against the wall time
per simulated second, one colour per integrator, one marker per number of control points, the
Pareto front (the runs no other run beats on both axes) as a line. Unstable runs and runs
stopped at the wall-time budget are left out (listed in the CSV with error inf). How to read it: the lower left is better; a point on the
front is the cheapest way to reach its accuracy; along one colour, moving right is a smaller
time step or more control points.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from integrator_colours import COLOURS  # noqa: E402  (beside this script)

MARKERS = ["o", "s", "^", "D", "v", "P", "X"]


def plot(path):
    meaning = ""
    rows = []
    with open(path, newline="") as f:
        lines = f.readlines()
    if lines and lines[0].startswith("#"):
        meaning = lines[0][1:].strip()
        lines = lines[1:]
    for row in csv.DictReader(lines):
        rows.append(row)
    stable = [r for r in rows if r["stable"] == "1" and math.isfinite(float(r["error"])) and float(r["error"]) > 0]
    if not stable:
        print(f"{path}: no stable run to plot")
        return
    problem = rows[0]["problem"]
    sizes = sorted({int(r["control_points"]) for r in rows})
    marker = {n: MARKERS[i % len(MARKERS)] for i, n in enumerate(sizes)}

    fig, ax = plt.subplots(figsize=(9, 6.5))
    for integrator, colour in COLOURS.items():
        for n in sizes:
            pts = [r for r in stable if r["integrator"] == integrator and int(r["control_points"]) == n]
            if pts:
                ax.scatter([float(r["wall_per_sim_s"]) for r in pts], [float(r["error"]) for r in pts], c=colour,
                           marker=marker[n], s=28, alpha=0.8, edgecolors="none")
    front = sorted((r for r in stable if r["pareto"] == "1"), key=lambda r: float(r["wall_per_sim_s"]))
    if front:
        xs = [float(r["wall_per_sim_s"]) for r in front]
        ys = [float(r["error"]) for r in front]
        ax.step(xs, ys, where="post", color="black", linewidth=1.2, label="Pareto front")
        ax.scatter(xs, ys, facecolors="none", edgecolors="black", s=80, linewidths=1.2)
    slow = sum(1 for r in rows if r.get("over_budget") == "1")
    unstable = len(rows) - len(stable) - slow
    # Legends: colours (integrators) and markers (n).
    for integrator, colour in COLOURS.items():
        if any(r["integrator"] == integrator for r in rows):
            ax.scatter([], [], c=colour, marker="o", label=integrator)
    for n in sizes:
        ax.scatter([], [], c="black", marker=marker[n], label=f"n = {n}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per simulated second (s/s), one thread")
    ax.set_ylabel("error against the analytic solution")
    ax.set_title(f"{problem}: run time against error ({len(stable)} stable runs; not shown: {unstable} unstable"
                 + (f", {slow} over the time budget" if slow else "") + ")")
    if meaning:
        fig.text(0.01, 0.005, meaning, fontsize=8)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="best")
    out = os.path.join(os.path.dirname(path) or ".", f"pareto_{problem}.png")
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) < 2:
        print(__doc__)
        sys.exit(2)
    for p in sys.argv[1:]:
        plot(p)
