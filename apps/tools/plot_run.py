#!/usr/bin/python3
"""Pictures of a `filum run` output folder, for a quick look without ParaView.

  python3 apps/tools/plot_run.py out/hanging_thread

writes, into the same folder:
  snapshots.png  the curve of every body at a dozen times, seen from the side (x–z) and from
                 above (x–y), coloured from early (light) to late (dark);
  energy.png     kinetic, potential and total energy over time, and the largest constraint
                 violation (log scale).
"""
import argparse
import csv
import math
import os
import sys
from collections import defaultdict

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read_curves(path):
    """{time: {body: [(x, y, z), ...]}} from curve.csv."""
    frames = defaultdict(lambda: defaultdict(list))
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            frames[float(row["time"])][row["body"]].append(
                (float(row["x"]), float(row["y"]), float(row["z"])))
    return frames


def read_columns(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    return {key: [float(r[key]) for r in rows] for key in rows[0]} if rows else {}


def plot_snapshots(frames, out):
    times = sorted(frames)
    picks = [times[round(i * (len(times) - 1) / 11)] for i in range(12)] if len(times) > 12 else times
    fig, axes = plt.subplots(1, 2, figsize=(12, 5))
    cmap = plt.get_cmap("viridis_r")
    for k, t in enumerate(picks):
        colour = cmap(0.15 + 0.85 * k / max(1, len(picks) - 1))
        for body, pts in frames[t].items():
            xs, ys, zs = zip(*pts)
            axes[0].plot(xs, zs, color=colour, lw=1.5, label=f"t = {t:.2f} s" if body == next(iter(frames[t])) else None)
            axes[1].plot(xs, ys, color=colour, lw=1.5)
    for ax, (a, b) in zip(axes, [("x", "z"), ("x", "y")]):
        ax.set_xlabel(f"{a} (m)")
        ax.set_ylabel(f"{b} (m)")
        ax.set_aspect("equal", adjustable="datalim")
        ax.grid(True, alpha=0.3)
    axes[0].set_title("side view (x–z)")
    axes[1].set_title("top view (x–y)")
    axes[0].legend(fontsize=7, loc="best")
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def plot_energy(columns, out):
    fig, axes = plt.subplots(1, 2, figsize=(12, 4))
    t = columns["time"]
    for key in ("kinetic", "potential", "total"):
        axes[0].plot(t, columns[key], label=key)
    axes[0].set_xlabel("time (s)")
    axes[0].set_ylabel("energy (J)")
    axes[0].legend()
    axes[0].grid(True, alpha=0.3)
    # Exactly zero (the start, a frame where the rows hold to the last bit) cannot be drawn on a
    # log scale: leave those frames out rather than plotting a 1e-300 spike.
    shown = [(ti, v) for ti, v in zip(t, columns["max_violation"]) if v > 0]
    if shown:
        axes[1].semilogy([p[0] for p in shown], [p[1] for p in shown])
    else:
        axes[1].text(0.5, 0.5, "no constraint violation (exactly 0)", ha="center", transform=axes[1].transAxes)
    axes[1].set_xlabel("time (s)")
    axes[1].set_ylabel("max constraint violation (m)")
    axes[1].grid(True, alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", help="output folder of `filum run`")
    args = parser.parse_args()
    curve = os.path.join(args.folder, "curve.csv")
    energy = os.path.join(args.folder, "energy.csv")
    if not os.path.exists(curve):
        sys.exit(f"{curve}: not found (run `filum run SCENE --out {args.folder}` first)")
    frames = read_curves(curve)
    plot_snapshots(frames, os.path.join(args.folder, "snapshots.png"))
    columns = read_columns(energy)
    if columns:
        plot_energy(columns, os.path.join(args.folder, "energy.png"))
    print(f"wrote {args.folder}/snapshots.png and {args.folder}/energy.png ({len(frames)} frames)")


if __name__ == "__main__":
    main()
