#!/usr/bin/python3
"""Stability map, from the CSV of apps/bench/stability_map.

  /usr/bin/python3 apps/tools/plot_stability.py stability_map.csv

writes stability_map.png next to it: the largest stable time step of each integrator against the
Young's modulus (log-log), with the explicit limits 2/ω_max (symplectic Euler) and 2√2/ω_max (RK4)
computed from the measured stiffest frequency ω_max, and the runs stable at the largest step tried
(implicit schemes) drawn as upward triangles. How to read it: above a curve the integrator blows up;
the explicit curves fall as E^(-1/2) (ω_max ∝ √E); the real 3-0 suture is E = 2 GPa.
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from integrator_colours import COLOURS  # noqa: E402  (beside this script)



def main(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    fig, ax = plt.subplots(figsize=(8, 6))
    for integrator, colour in COLOURS.items():
        pts = sorted((r for r in rows if r["integrator"] == integrator), key=lambda r: float(r["youngs_modulus"]))
        pts = [r for r in pts if float(r["largest_stable_dt"]) > 0]
        if not pts:
            continue
        xs = [float(r["youngs_modulus"]) for r in pts]
        ys = [float(r["largest_stable_dt"]) for r in pts]
        ax.plot(xs, ys, "-", color=colour, label=integrator)
        for x, y, r in zip(xs, ys, pts):
            ax.scatter([x], [y], color=colour, marker="^" if r["capped"] == "1" else "o", s=40)
    moduli = sorted({float(r["youngs_modulus"]) for r in rows})
    omega = {float(r["youngs_modulus"]): float(r["omega_max"]) for r in rows}
    ax.plot(moduli, [2 / omega[e] for e in moduli], ":", color="tab:orange", label="2 / ω_max")
    ax.plot(moduli, [2 * math.sqrt(2) / omega[e] for e in moduli], ":", color="tab:blue", label="2√2 / ω_max")
    ax.scatter([], [], color="black", marker="^", label="stable at the largest step tried")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.axvline(2e9, color="black", alpha=0.3, linewidth=1)
    ax.text(2e9, 0.5, " 3-0 suture", fontsize=8, rotation=90, transform=ax.get_xaxis_transform())
    ax.set_xlabel("Young's modulus E (Pa)")
    ax.set_ylabel("largest stable time step (s)")
    ax.set_title("stability map: 10 cm thread, 20 control points, one end fixed, under gravity")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    out = os.path.join(os.path.dirname(path) or ".", "stability_map.png")
    fig.tight_layout()
    fig.savefig(out, dpi=120)
    plt.close(fig)
    print(f"wrote {out}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        print(__doc__)
        sys.exit(2)
    main(sys.argv[1])
