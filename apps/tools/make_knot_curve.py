#!/usr/bin/env python3
"""Print the initial control points of apps/scenes/knot.json: a loose overhand knot in a 2-0 silk
suture, relaxed onto its own contacts.

    apps/tools/make_knot_curve.py [--filum build/apps/filum] > points.json

1. The open trefoil of paper_knot.json, (sin t + 2 sin 2t, cos t − 2 cos 2t, −sin 3t) for
   t in [π + 0.4, 3π − 0.4], turned (x, y, z) → (x, z, −y) and scaled by 1.5 mm, with straight
   arms of 3 cm along −x (from its start) and +x (from its end), the two corners where the arms
   meet the trefoil rounded (moving average over ±2 mm), then 98 points equally spaced along it,
   interpolated by the uniform cubic B-spline of 100 control points (1.0 mm apart). Its
   parametric speed is uniform to 1 %, so the rest shape a straightened piece should reach is one
   the spline can take: control points sampled straight from the polyline left a 17 % dip of
   |P0'| at each corner, and once pulled straight out of the knot that piece kept a kink of
   ±0.3 % strain (1-2 N at E·A = 615 N). The curve has determinant 3 (an overhand knot once
   closed far away); nothing touches yet.
2. That curve is not at rest: a stiff thread bent into 1.5 mm loops springs open within a tenth
   of a millisecond (time scale R² √(ρA/EI) ≈ 5e-5 s), far too violent for 1 ms steps. It is
   relaxed with both ends held: 40 ms at dt = 20 µs with heavy viscous damping (2000 /s, so the
   loops creep onto each other instead of snapping), then 0.3 s in the scene's own settings
   (dt = 1 ms, 2 /s). The loops open until they rest on each other: a loose knot on its
   contacts, still of determinant 3.
Runs `filum run` twice (a few seconds) in a temporary folder and prints the last frame's control
points as a JSON array.
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import tempfile

SCALE, CUT, ARM, COUNT = 1.5e-3, 0.4, 0.03, 100


def trefoil(t):
    return (math.sin(t) + 2 * math.sin(2 * t), math.cos(t) - 2 * math.cos(2 * t), -math.sin(3 * t))


def resample(poly, count):
    """count points equally spaced along the polyline poly."""
    cumulative = [0.0]
    for p, q in zip(poly, poly[1:]):
        cumulative.append(cumulative[-1] + math.dist(p, q))
    points, j = [], 0
    for k in range(count):
        s = cumulative[-1] * k / (count - 1)
        while j + 2 < len(cumulative) and cumulative[j + 1] < s:
            j += 1
        u = (s - cumulative[j]) / (cumulative[j + 1] - cumulative[j])
        points.append([poly[j][c] + u * (poly[j + 1][c] - poly[j][c]) for c in range(3)])
    return points


def round_corners(poly, corners, width, reach):
    """Moving average over ±width along the polyline within reach of the corners (tapering to
    nothing at 2 reach): the arms meet the trefoil at an angle, which a B-spline would cut."""
    points = resample(poly, 8000)
    h = sum(math.dist(p, q) for p, q in zip(points, points[1:])) / (len(points) - 1)
    at = [min(range(len(points)), key=lambda i: math.dist(points[i], c)) for c in corners]
    smoothed = []
    for i in range(len(points)):
        d = min(abs(i - j) for j in at) * h
        w = int(width * min(1.0, max(0.0, 2.0 - d / reach)) / h)
        w = min(w, i, len(points) - 1 - i)
        smoothed.append([sum(points[k][c] for k in range(i - w, i + w + 1)) / (2 * w + 1) for c in range(3)])
    return smoothed


def interpolating_control_points(points):
    """Control points of the uniform cubic B-spline through `points` at its breakpoints,
    (q_j + 4 q_j+1 + q_j+2)/6 = p_j, with P'' = 0 at both ends (q_0 − 2 q_1 + q_2 = 0): a curve
    that keeps to the equally spaced points, so that its parametric speed is nearly uniform."""
    m = len(points)
    n = m + 2
    rows = [[0.0] * n for _ in range(n)]
    rhs = [[0.0] * 3 for _ in range(n)]
    rows[0][0:3] = [1.0, -2.0, 1.0]
    for j in range(m):
        rows[j + 1][j:j + 3] = [1 / 6, 4 / 6, 1 / 6]
        rhs[j + 1] = list(points[j])
    rows[n - 1][n - 3:n] = [1.0, -2.0, 1.0]
    for i in range(n):  # Gaussian elimination with partial pivoting (banded, n = 100)
        p = max(range(i, min(n, i + 3)), key=lambda r: abs(rows[r][i]))
        rows[i], rows[p], rhs[i], rhs[p] = rows[p], rows[i], rhs[p], rhs[i]
        for r in range(i + 1, min(n, i + 4)):
            f = rows[r][i] / rows[i][i]
            for c in range(i, min(n, i + 5)):
                rows[r][c] -= f * rows[i][c]
            for c in range(3):
                rhs[r][c] -= f * rhs[i][c]
    x = [[0.0] * 3 for _ in range(n)]
    for i in range(n - 1, -1, -1):
        for c in range(3):
            x[i][c] = (rhs[i][c] - sum(rows[i][k] * x[k][c] for k in range(i + 1, min(n, i + 5)))) / rows[i][i]
    return x


def initial_points():
    dense = 4000
    t0, t1 = math.pi + CUT, 3 * math.pi - CUT
    knot = []
    for k in range(dense + 1):
        x, y, z = trefoil(t0 + (t1 - t0) * k / dense)
        knot.append((SCALE * x, SCALE * z, -SCALE * y))  # cut lobe on top
    a, b = knot[0], knot[-1]
    m = dense // 4
    poly = [(a[0] - ARM * k / m, a[1], a[2]) for k in range(m, 0, -1)] + knot + \
           [(b[0] + ARM * k / m, b[1], b[2]) for k in range(1, m + 1)]
    poly = round_corners(poly, [a, b], 2e-3, 3e-3)
    return interpolating_control_points(resample(poly, COUNT - 2))


def scene(points, dt, duration, damping):
    return {
        "name": "knot relaxation", "dt": dt, "duration": duration, "gravity": [0, 0, -9.81],
        "integrator": {"type": "ImplicitEuler", "newton_iterations": 1},
        "constraint_solver": {"type": "LagrangeMultiplierSolver", "contact_iterations": 100},
        "collision": {"type": "ContactPipeline", "response": "unilateral", "friction": 0.2,
                      "max_penetration": 0.1, "max_slide": 1.5e-4, "contact_halvings": 3},
        "output": {"interval": duration, "curve_samples": 16},
        "nodes": [{"name": "thread", "components": [
            {"type": "DynamicSpline", "radius": 1.5e-4, "density": 1300, "control_points": points},
            {"type": "GreenLagrangeStretching", "youngs_modulus": 8.7e9, "jacobian": "definite"},
            {"type": "ParametricBending", "youngs_modulus": 5e8},
            {"type": "ViscousDamping", "coefficient": damping},
            {"type": "SphereCollisionModel", "spacing": 3e-4},
            {"type": "FixedPointConstraint", "name": "left end", "abscissa": 0.0},
            {"type": "FixedPointConstraint", "name": "right end", "abscissa": 1.0}]}]}


def run(filum, document, folder):
    path = os.path.join(folder, "scene.json")
    with open(path, "w") as f:
        json.dump(document, f)
    out = os.path.join(folder, "run")
    subprocess.run([filum, "run", path, "--out", out, "--quiet"], check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "control_points.csv"), newline="") as f:
        rows = list(csv.DictReader(f))
    last = rows[-1]["time"]
    return [[float(r["x"]), float(r["y"]), float(r["z"])] for r in rows if r["time"] == last]


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--filum", default="build/apps/filum")
    args = parser.parse_args()
    points = initial_points()
    with tempfile.TemporaryDirectory() as folder:
        points = run(args.filum, scene(points, 2e-5, 0.04, 2000.0), folder)
        points = run(args.filum, scene(points, 1e-3, 0.3, 2.0), folder)
    print("[" + ",\n ".join("[%.6e, %.6e, %.6e]" % tuple(p) for p in points) + "]")


if __name__ == "__main__":
    sys.exit(main())
