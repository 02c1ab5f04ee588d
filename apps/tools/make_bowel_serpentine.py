#!/usr/bin/env python3
"""Lays a small bowel in the abdominal cavity as a serpentine and lets it settle: the control
points of apps/scenes/intestine.json.

The serpentine: rows of 20 cm along x, 4.5 cm apart in y, joined by half circles, at z = -3 cm in
the cavity of apps/scenes/data/abdomen.off, resampled every 2.5 cm of its length (41 control
points for 1 m). The scene it writes is intestine.json without its instruments; `--settle` runs
it for 1.5 s with filum (the bowel falls onto the posterior wall and its turns relax into loops)
and prints the control points of the last frame as JSON, which intestine.json starts from.

    python3 apps/tools/make_bowel_serpentine.py --out /tmp/serpentine.json \\
        [--settle build/apps/filum] [--length 1.0] [--spacing 0.025]
"""
import argparse
import csv
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile


def serpentine(length, spacing, row_length=0.2, pitch=0.045, y0=-0.1):
    turn = pitch / 2
    dense, y, forward, total = [], y0, True, 0.0
    while total < length + 0.1:
        xs = [-row_length / 2 + row_length * i / 400 for i in range(401)]
        if not forward:
            xs = xs[::-1]
        dense += [(x, y) for x in xs]
        sign = 1 if forward else -1
        dense += [(xs[-1] + sign * turn * math.cos(-math.pi / 2 + math.pi * i / 200),
                   y + turn + turn * math.sin(-math.pi / 2 + math.pi * i / 200)) for i in range(1, 200)]
        y += pitch
        forward = not forward
        total = sum(math.dist(dense[i], dense[i + 1]) for i in range(len(dense) - 1))
    out, walked, target = [dense[0]], 0.0, spacing
    for a, b in zip(dense, dense[1:]):
        d = math.dist(a, b)
        while walked + d >= target - 1e-12 and target <= length + 1e-9:
            t = (target - walked) / d
            out.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
            target += spacing
        walked += d
    return out


def scene(points, duration):
    k, rho_a = 200.0, 1050 * math.pi * 0.015 ** 2
    data = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "scenes", "data", "abdomen.off")
    return {"name": "bowel serpentine settling", "dt": 1e-3, "duration": duration, "gravity": [0, 0, -9.81],
            "integrator": {"type": "ImplicitEuler"},
            "collision": {"type": "ContactPipeline", "response": "unilateral", "friction": 0.3},
            "output": {"interval": 0.01, "curve_samples": 300, "knots": False},
            "nodes": [{"name": "bowel", "components": [
                {"type": "DynamicSpline", "control_points": points, "radius": 0.015, "density": 1050},
                {"type": "GreenLagrangeStretching", "youngs_modulus": 1e5},
                {"type": "CurvatureBending", "youngs_modulus": 1e5},
                {"type": "ViscousDamping", "coefficient": 2.0},
                {"type": "TissueAttachment", "count": 60, "stiffness": k, "damping": round(2 * math.sqrt(k * rho_a), 2),
                 "rest_length": "initial", "root": {"from": [-0.06, 0.05, -0.07], "to": [0.06, -0.05, -0.07]}},
                {"type": "SphereCollisionModel", "spacing": 0.015, "self_collision": True}]},
                {"name": "abdomen", "components": [
                    {"type": "TriangleMeshObstacle", "file": os.path.abspath(data), "side": "inside", "friction": 0.2}]}]}


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", required=True, help="the serpentine scene to write")
    parser.add_argument("--settle", metavar="FILUM", help="run it with this filum binary and print the settled points")
    parser.add_argument("--length", type=float, default=1.0)
    parser.add_argument("--spacing", type=float, default=0.025)
    parser.add_argument("--duration", type=float, default=1.5)
    args = parser.parse_args()
    points = [[round(x, 5), round(y, 5), -0.03] for x, y in serpentine(args.length, args.spacing)]
    with open(args.out, "w") as f:
        json.dump(scene(points, args.duration), f, indent=1)
    if not args.settle:
        return
    folder = tempfile.mkdtemp()
    try:
        subprocess.run([args.settle, "run", args.out, "--out", folder, "-q"], check=True, stdout=sys.stderr)
        rows = list(csv.DictReader(open(os.path.join(folder, "control_points.csv"))))
        last = max(float(r["time"]) for r in rows)
        print(json.dumps([[round(float(r[c]), 5) for c in "xyz"] for r in rows if float(r["time"]) == last]))
    finally:
        shutil.rmtree(folder)


if __name__ == "__main__":
    main()
