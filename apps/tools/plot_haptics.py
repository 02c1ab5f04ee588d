#!/usr/bin/python3
"""The force a haptic device got, and its servo loop's period, from a run's haptics.csv.

  /usr/bin/python3 apps/tools/plot_haptics.py out/haptic_grasp [--out haptics.png]

haptics.csv (written by `filum run` for a scene with a "haptics" block) has one row per servo
tick. The picture has two panels over time:
  force   |F| commanded by the local model and |F| sent after the safety stage (clamp, slew,
          watchdog), with the device's button held shaded — where the two differ, a limit acted;
  period  the servo loop's period (ms): exactly 1 ms in lockstep, the wall clock's in thread mode.
"""
import argparse
import csv
import math
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def read(path):
    rows = {"time": [], "period": [], "commanded": [], "sent": [], "buttons": []}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            rows["time"].append(float(row["time"]))
            rows["period"].append(1e3 * float(row["period"]))
            c = [float(row[f"commanded_{a}"]) for a in "xyz"]
            s = [float(row[f"sent_{a}"]) for a in "xyz"]
            rows["commanded"].append(math.sqrt(sum(v * v for v in c)) if all(map(math.isfinite, c)) else float("nan"))
            rows["sent"].append(math.sqrt(sum(v * v for v in s)))
            rows["buttons"].append(int(row["buttons"]))
    return rows


def shade_buttons(ax, t, buttons):
    start = None
    for k, b in enumerate(buttons + [0]):
        if b and start is None:
            start = t[k]
        if not b and start is not None:
            ax.axvspan(start, t[min(k, len(t) - 1)], color="0.9", zorder=0)
            start = None


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("folder", help="output folder of `filum run` holding haptics.csv")
    parser.add_argument("--out", help="picture (default: <folder>/haptics.png)")
    args = parser.parse_args()
    path = os.path.join(args.folder, "haptics.csv")
    if not os.path.exists(path):
        sys.exit(f"{path}: no such file (run a scene with a \"haptics\" block first)")
    r = read(path)
    if not r["time"]:
        sys.exit(f"{path}: no servo tick recorded")
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(9, 6), sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    shade_buttons(top, r["time"], r["buttons"])
    top.plot(r["time"], r["commanded"], color="tab:blue", lw=1.2, label="commanded (local model)")
    top.plot(r["time"], r["sent"], color="tab:red", lw=1.2, ls="--", label="sent (after clamp, slew, watchdog)")
    top.set_ylabel("|F| on the stylus (N)")
    top.legend(loc="upper right", fontsize=8)
    top.set_title(f"{os.path.basename(os.path.normpath(args.folder))}: force at the stylus (grey: button held)")
    bottom.plot(r["time"], r["period"], color="tab:green", lw=0.8)
    bottom.set_ylim(0.0, max(2.0, 1.1 * max(r["period"])))  # from zero: jitter against the period itself
    bottom.set_ylabel("servo period (ms)")
    bottom.set_xlabel("time (s)")
    fig.tight_layout()
    out = args.out or os.path.join(args.folder, "haptics.png")
    fig.savefig(out, dpi=110)
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
