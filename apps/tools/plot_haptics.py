#!/usr/bin/python3
"""The force a haptic device got, and its servo loop's period, from a run's haptics.csv.

  /usr/bin/python3 apps/tools/plot_haptics.py out/haptic_grasp [--out haptics.png]

haptics.csv (written by `filum run` for a scene with a "haptics" block, or a "navigation" block
with a "device" on an instrument's hub) has one row per servo tick. The picture has panels over
time:
  force   |F| commanded by the local model and |F| sent after the safety stage (clamp, slew,
          watchdog), with the device's button held shaded — where the two differ, a limit acted;
  torque  (when one was commanded) the torque about the stylus's axis, commanded and sent (mN·m;
          a device without a motor on its gimbal gets none), and the stylus's roll;
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
    rows = {"time": [], "period": [], "commanded": [], "sent": [], "buttons": [], "roll": [], "torque_commanded": [],
            "torque_sent": []}
    with open(path, newline="") as f:
        for row in csv.DictReader(f):
            rows["time"].append(float(row["time"]))
            rows["period"].append(1e3 * float(row["period"]))
            c = [float(row[f"commanded_{a}"]) for a in "xyz"]
            s = [float(row[f"sent_{a}"]) for a in "xyz"]
            rows["commanded"].append(math.sqrt(sum(v * v for v in c)) if all(map(math.isfinite, c)) else float("nan"))
            rows["sent"].append(math.sqrt(sum(v * v for v in s)))
            rows["buttons"].append(int(row["buttons"]))
            for key in ("roll", "torque_commanded", "torque_sent"):  # (older files have no such columns)
                rows[key].append(float(row[key]) if row.get(key) not in (None, "") else 0.0)
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
    torque = any(v != 0.0 for v in r["torque_commanded"])
    ratios = [2, 1.5, 1] if torque else [2, 1]
    fig, axes = plt.subplots(len(ratios), 1, figsize=(9, 6 + 2 * torque), sharex=True,
                             gridspec_kw={"height_ratios": ratios})
    top, bottom = axes[0], axes[-1]
    shade_buttons(top, r["time"], r["buttons"])
    top.plot(r["time"], r["commanded"], color="tab:blue", lw=1.2, label="commanded (local model)")
    top.plot(r["time"], r["sent"], color="tab:red", lw=1.2, ls="--", label="sent (after clamp, slew, watchdog)")
    top.set_ylabel("|F| on the stylus (N)")
    top.legend(loc="upper right", fontsize=8)
    top.set_title(f"{os.path.basename(os.path.normpath(args.folder))}: force at the stylus (grey: button held)")
    if torque:
        middle = axes[1]
        shade_buttons(middle, r["time"], r["buttons"])
        middle.plot(r["time"], [1e3 * v for v in r["torque_commanded"]], color="tab:blue", lw=1.2, label="commanded")
        middle.plot(r["time"], [1e3 * v for v in r["torque_sent"]], color="tab:red", lw=1.2, ls="--", label="sent")
        middle.set_ylabel("torque about the\nstylus (mN·m)")
        roll = middle.twinx()
        roll.plot(r["time"], [math.degrees(v) for v in r["roll"]], color="0.4", lw=0.8, label="stylus roll")
        roll.set_ylabel("roll (°)")
        middle.legend(loc="upper left", fontsize=8)
        roll.legend(loc="upper right", fontsize=8)
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
