#!/usr/bin/env python3
"""Write knot_security_square.json and knot_security_granny.json (into --out; not shipped in
apps/scenes: see Status): a stitch tied by two single throws in a 2-0 silk suture, of opposite
senses (the square knot) or of the same sense (the granny), drawn tight by its tails — the first
half of the knot-security test of issue 30 (the tails pulled apart with a rising force: the
square knot should hold, the granny slip first).

    apps/tools/make_knot_security.py [--filum build/apps/filum] [--out DIR (default .)]

1. The stitch, in units of U = 1.5 mm: the construction of tests/collision/knot_type_test.cpp
   (`suture`), which knot_type names square and granny. The thread runs straight through the
   tissue between two holes at x = ±U, z = 0; its strands rise from the holes and are tied by
   the throws, one above the other: in a throw at height h the strand on the left winds round a
   horizontal axis (y = 0, z = h) as a helix of radius U/2, turning 3π, the other runs along
   the axis. The tails end up and apart with straight arms of 1.5 cm. Corners rounded (moving
   average over ±0.3 mm), interpolated by a uniform cubic B-spline, control points 0.4 mm apart
   (179 points, 7 cm of thread).
2. Relaxed onto its own contacts as apps/tools/make_knot_curve.py relaxes knot.json's curve, with
   both ends and both holes held (FixedPointConstraint): 40 ms at dt = 20 µs and 2000 /s of
   viscous damping, then 0.3 s at 1 ms.
3. The scene: knot.json's material and numerics (2-0 silk, E·A = 615 N, μ = 0.2, backward Euler)
   at dt = 0.5 ms, 20 /s of viscous damping; the holes are SlidingPointConstraints (the thread
   slides through the tissue), the tails are drawn 1 cm outwards along x on smooth paths over
   0.02-1.2 s. The figures below read the tails' tension by hand (this tool does not) as
   E·A ε at s = 0.01 and 0.99, ε = (|P'|²/|P0'|² − 1)/2 from the run's control_points.csv (P0:
   the relaxed curve, the stretching's rest state).

Status (measured 2026-11-28, not yet a test):
- Both knots keep their type in knot.csv at every frame.
- Square: drawn tight, the loop cinches from 30 to 10 mm and the knot holds (slip 0.3 mm/s at the
  end) with the tails at 4.4-4.9 N, 12 contacts pressing with 25 N in all.
- Granny: the run stops at t = 0.85 s with the tails at 1.3 N ("the bodies swept so far that
  contact detection found more candidate pairs than its budget"). That is a failed step, rolled
  back, not a slip: from 0.844 s the whole thread swings 0.5-1.8 mm per step, and the knot's
  contact force grows from 1.7 to 13 N over two steps. Edited by hand: with the holes as
  FixedPointConstraints the same granny runs to 1.2 s; so it does with "friction": 0.01 (N·s/m) in its holes, the
  tails then at 2.9-3.0 N (not with 5e-4); with "newton_chord_steps": false it fails at 0.86 s.
- Edited by hand: at dt = 1 ms, the square stops the same way at 0.93 s, its tails at 27 N at
  0.90 s (its loop cinched to 17 mm, against 10 mm and 4.4-4.9 N at 0.5 ms: the drawn-tight
  state is not converged in dt).
- Edited by hand: with force-controlled tails (PointLoad ramps to 3 N), the free tails whip, and the granny
  stops at 0.22 s.
- Edited by hand, holes as FixedPointConstraints: tails drawn 3 cm at 1 cm/s, neither knot slips
  (loops cinch to 12 and 11 mm and jam; tails reach about 500 N, no break force set); tails let go
  at 0.95 s and the holes drawn apart from 1 s, both knots spring open before the holes move
  (the square's loop 18 -> 51 mm by 1.05 s, the granny's 17 -> 28-30 mm by 1.2 s). docs/applications.md, "Which knot was tied", has the details.
So the contact step does not yet survive a jammed knot loaded by a few newtons, which the
security test needs: the granny's slip cannot be told from a failed step.
"""
import argparse
import json
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_knot_curve as knot  # noqa: E402

U = 1.5e-3        # m: the unit of the stitch's construction
SPACING = 4e-4    # m: control points apart
ARM = 0.015       # m: the tails' straight arms
TAIL_PULL = 1e-2  # m: each tail drawn outwards


def line(strand, q, n=20):
    a = strand[-1]
    for i in range(1, n + 1):
        strand.append(tuple(a[c] + (q[c] - a[c]) * i / n for c in range(3)))


def stitch(senses):
    """The thread's polyline (in m) and the indices of its two holes in it."""
    left, right = [(-1.0, 0.0, 0.0)], [(1.0, 0.0, 0.0)]
    h = 1.0
    for sense in senses:
        winding, straight = (left, right) if left[-1][0] < 0 else (right, left)
        line(winding, (-1.0, 0.0, h - 0.5))
        line(straight, (1.0, 0.0, h - 0.5))
        line(straight, (1.0, 0.0, h))
        samples = 300
        for i in range(1, samples + 1):
            u = i / samples
            a = sense * 3 * math.pi * u
            winding.append((-1 + 2 * u, 0.5 * math.sin(a), h - 0.5 * math.cos(a)))
        line(straight, (-1.0, 0.0, h), 40)
        line(straight, (-1.0, 0.0, h + 0.5))
        h += 1.5
    for strand in (left, right):
        line(strand, (3 * strand[-1][0], 0.0, h + 2))
        x, z = strand[-1][0], strand[-1][2]
        line(strand, (x + math.copysign(ARM / U, x), 0.0, z), 100)
    bight = [(-1 + 2 * i / 40, 0.0, 0.0) for i in range(1, 40)]
    thread = left[::-1] + bight + right
    holes = (len(left) - 1, len(left) + len(bight))
    return [tuple(U * c for c in p) for p in thread], holes


def control_points(poly, holes):
    """Control points SPACING apart along the rounded polyline, and the holes' abscissas."""
    corners = [poly[holes[0]], poly[holes[1]]]
    length = sum(math.dist(p, q) for p, q in zip(poly, poly[1:]))
    count = int(round(length / SPACING)) + 1
    rounded = knot.round_corners(poly, corners, 3e-4, 5e-4)
    at = []
    for c in corners:  # arc length of the rounded curve's point nearest to each hole
        best, run = (1e9, 0.0), 0.0
        for p, q in zip(rounded, rounded[1:]):
            d = math.dist(p, c)
            if d < best[0]:
                best = (d, run)
            run += math.dist(p, q)
        at.append(best[1] / run)
    return knot.interpolating_control_points(knot.resample(rounded, count - 2)), at


def relax_scene(points, holes, dt, duration, damping):
    document = knot.scene(points, dt, duration, damping)
    components = document["nodes"][0]["components"]
    for name, s in zip(("left hole", "right hole"), holes):
        components.append({"type": "FixedPointConstraint", "name": name, "abscissa": s})
    return document


def security_scene(name, points, holes):
    def at(s):  # the point of the uniform cubic B-spline at abscissa s
        n = len(points) - 3
        u = s * n
        j = min(int(u), n - 1)
        t = u - j
        b = [(1 - t) ** 3 / 6, (3 * t ** 3 - 6 * t ** 2 + 4) / 6, (-3 * t ** 3 + 3 * t ** 2 + 3 * t + 1) / 6, t ** 3 / 6]
        return [sum(b[k] * points[j + k][c] for k in range(4)) for c in range(3)]

    def moved(p, dx):
        return [round(p[0] + dx, 9), round(p[1], 9), round(p[2], 9)]

    ends = [at(0.0), at(1.0)]
    tail_paths = [[{"time": 0.02, "position": moved(p, 0.0)}, {"time": 1.2, "position": moved(p, sign * TAIL_PULL)}]
                  for p, sign in zip(ends, (-1, 1))]
    return {
        "name": f"knot security: {name} (2-0 silk, implicit 0.5 ms)", "dt": 5e-4, "duration": 1.2,
        "gravity": [0, 0, -9.81],
        "integrator": {"type": "ImplicitEuler", "newton_iterations": 1},
        "constraint_solver": {"type": "LagrangeMultiplierSolver", "contact_iterations": 100, "sparse_above": 1000,
                              "newton_presweeps": 2},
        "collision": {"type": "ContactPipeline", "response": "unilateral", "friction": 0.2,
                      "max_penetration": 0.1, "max_slide": 1.5e-4, "contact_halvings": 3},
        "output": {"interval": 0.005, "curve_samples": 300},
        "camera": {"position": [0.0, -0.12, 0.012], "look_at": [0.0, 0.0, 0.008], "up": [0, 0, 1],
                   "fov": 30, "size": [960, 540], "background": [1, 1, 1]},
        "nodes": [{"name": "thread", "components": [
            {"type": "DynamicSpline", "basis": "uniform_cubic_bspline", "radius": 1.5e-4, "density": 1300,
             "control_points": [[float("%.6e" % c) for c in p] for p in points]},
            {"type": "GreenLagrangeStretching", "youngs_modulus": 8.7e9, "jacobian": "definite"},
            {"type": "ParametricBending", "youngs_modulus": 5e8},
            {"type": "ViscousDamping", "coefficient": 20.0},
            {"type": "SphereCollisionModel", "spacing": 3e-4},
            {"type": "FixedPointConstraint", "name": "left tail", "abscissa": 0.0, "interpolation": "smooth",
             "path": tail_paths[0]},
            {"type": "FixedPointConstraint", "name": "right tail", "abscissa": 1.0, "interpolation": "smooth",
             "path": tail_paths[1]},
            {"type": "SlidingPointConstraint", "name": "left hole", "abscissa": round(holes[0], 6)},
            {"type": "SlidingPointConstraint", "name": "right hole", "abscissa": round(holes[1], 6)},
            {"type": "GeneralizedCylinder", "radius": 1.5e-4}]}]}


HEADER = """// Knot security, first half: a stitch in 2-0 silk tied by two single throws{what},
// drawn tight by its tails (each 1 cm outwards along x over 0.02-1.2 s), the thread sliding
// through its two holes in the tissue. Written by apps/tools/make_knot_security.py: its
// docstring says how the curve was made and relaxed, and what the runs do so far.
"""


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--filum", default="build/apps/filum")
    parser.add_argument("--out", default=".")
    args = parser.parse_args()
    for name, senses, what in (("square", (1, -1), " of opposite senses (a square knot)"),
                               ("granny", (1, 1), " of the same sense (a granny knot)")):
        poly, hole_index = stitch(senses)
        points, holes = control_points(poly, hole_index)
        with tempfile.TemporaryDirectory() as folder:
            points = knot.run(args.filum, relax_scene(points, holes, 2e-5, 0.04, 2000.0), folder)
            points = knot.run(args.filum, relax_scene(points, holes, 1e-3, 0.3, 2.0), folder)
        path = os.path.join(args.out, f"knot_security_{name}.json")
        with open(path, "w") as f:
            f.write(HEADER.format(what=what))
            f.write(json.dumps(security_scene(name, points, holes), indent=1))
            f.write("\n")
        print(f"wrote {path} ({len(points)} control points, holes at s = {holes[0]:.4f}, {holes[1]:.4f})")


if __name__ == "__main__":
    sys.exit(main())
