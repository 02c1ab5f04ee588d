#!/usr/bin/env python3
"""Plot of bench_realtime: largest strain of the benchmark rope against wall time per
simulated millisecond, one point per scheme and control point count; the vertical line is real
time (1 ms per ms). Reads DIR/realtime.csv, writes DIR/realtime.png.

    python3 apps/tools/plot_realtime.py apps/bench/results/realtime
"""
import csv
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

SCHEME_COLOURS = {
    "implicit Euler linearized": "tab:red",
    "implicit Euler lin. fresh": "tab:purple",
    "implicit Euler B-W only": "tab:pink",
    "implicit Euler Newton": "tab:brown",
    "implicit midpoint lin.": "tab:green",
    "symplectic Euler": "tab:orange",
    "RK4": "tab:blue",
    "Bullet 4 it.": "tab:olive",
    "Bullet 64 it.": "tab:cyan",
    "MuJoCo rope": "black",
}
MARKERS = {30: "o", 50: "s", 165: "D", 1000: "^"}


def main(directory: str) -> None:
    folder = Path(directory)
    rows = [r for r in csv.DictReader(open(folder / "realtime.csv")) if r["problem"] == "rope" and r["status"] == "ok"]
    fig, ax = plt.subplots(figsize=(8, 5.5))
    for scheme, colour in SCHEME_COLOURS.items():
        for n, marker in MARKERS.items():
            points = [r for r in rows if r["scheme"] == scheme and int(r["n"]) == n]
            if not points:
                continue
            x = [float(r["wall_ms_per_sim_ms"]) for r in points]
            y = [max(float(r["max_strain"]), 1e-12) for r in points]
            ax.scatter(x, y, color=colour, marker=marker, s=45)
    ax.axvline(1.0, color="black", linestyle="--", linewidth=1)
    ax.text(1.05, ax.get_ylim()[0] if ax.get_ylim()[0] > 0 else 1e-5, "real time", rotation=90, va="bottom")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("wall time per simulated ms (ms), median")
    ax.set_ylabel("largest strain |ε| over the run")
    ax.set_title("Rope 1 m, 0.1 kg, r = 5 mm, E = 1e8 Pa, one end held (bench_realtime)")
    # Explicit schemes run 0.05 s only (their steps are ~1e4 times smaller): the rope has barely
    # started to fall, so their strain is not comparable with the 2 s implicit runs.
    def label(scheme: str) -> str:
        if scheme == "MuJoCo rope":  # joints in generalized coordinates: exactly inextensible
            return scheme + " (strain 0, drawn at 1e-12)"
        return scheme + (" (0.05 s run)" if scheme in ("symplectic Euler", "RK4") else "")

    handles = [plt.Line2D([], [], color=c, marker="o", linestyle="", label=label(s)) for s, c in SCHEME_COLOURS.items()]
    handles += [plt.Line2D([], [], color="gray", marker=m, linestyle="", label=f"n = {n}") for n, m in MARKERS.items()]
    ax.legend(handles=handles, fontsize=8, loc="best")
    ax.grid(True, which="both", alpha=0.3)
    fig.tight_layout()
    fig.savefig(folder / "realtime.png", dpi=110)
    print(f"wrote {folder / 'realtime.png'}")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "apps/bench/results/realtime")
