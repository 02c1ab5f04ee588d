#!/usr/bin/env python3
"""Writes apps/scenes/stitch.json: a 3/8-circle needle driven through both lips of a wound by two
needle holders that turn it about its centre, as a surgeon's wrist does (haptics/wound.hpp).

The needle (radius R = 8 mm) lies in the plane x = 0 across the wound (the wound runs along x, its
lips' cut faces at y = ±1 mm, the skin at z = 0). Its centre is set so that its circle crosses the
skin 6 mm either side of the wound's axis (5 mm from each cut face: the bite), at a height
sqrt(R² − 6²) mm. A holder's jaws cross the wire 6 mm from their hinge with the shaft along +x
(perpendicular to the needle's plane), opening along the radius where they hold it: roll =
angle − 90°. Turning the needle by Δ about its centre turns the hinge by Δ on the circle, given as
keyframes every 12.5°. Between them the path interpolates each coordinate (monotone cubics) and the
turn (slerp) apart, so the tip strays from the circle a little: it enters the skin 4.7 mm from the
cut face, not 5 (measured; metrics.json's wound holes).

Holder A holds the wire 10° from the swage and turns the needle 125° over 0.2-1.7 s: the tip goes
in through the left lip's skin, out of its cut face, into the right lip's cut face and out of its
skin. Holder B takes the wire 10° from the tip at 1.75-1.85 s, A lets go at 2.0 s, and B turns the
needle 135° more over 2.1-3.1 s, until the swage is out, then draws it PULL_Y along +y and PULL_Z
up by 4.5 s. The thread leaves the swage along the needle's axis; its tail is held by an assistant who brings
its end towards the wound by 2.5 s.

    python3 apps/tools/make_stitch.py [--out apps/scenes]
"""
import argparse
import json
import math
import os

R, ARC, BITE_Y = 0.008, 2.356, 0.006
ZC = math.sqrt(R * R - BITE_Y * BITE_Y)
BETA = math.radians(85.0)  # the swage's angle at the start: the tip at −140°, 0.15 mm above the skin
HINGE_DX = -0.006
LENGTH, PULL_Y, PULL_Z = 0.15, 0.04, 0.09
TAIL = [0.04, -0.03, 0.01]


def wire(angle):
    """The needle's circle at an angle in its plane, from +y towards +z."""
    return [0.0, R * math.cos(angle), ZC + R * math.sin(angle)]


def rounded(p):
    return [round(c, 7) for c in p]


def key(t, grasp, jaw=None, first=False):
    p = wire(grasp)
    p[0] += HINGE_DX
    k = {"time": round(t, 4), "position": rounded(p), "roll": round(grasp - math.pi / 2, 6)}
    if first:
        k["direction"] = [1, 0, 0]
    if jaw is not None:
        k["jaw"] = jaw
    return k


def turn(t0, t1, grasp0, delta, n=10):
    return [key(t0 + (t1 - t0) * i / n, grasp0 + delta * i / n) for i in range(1, n + 1)]


def paths():
    d1, d2 = math.radians(125), math.radians(135)
    g_a = BETA + math.radians(10)
    a = [key(0.0, g_a, 1, True), key(0.1, g_a, 0)] + turn(0.2, 1.7, g_a, d1)
    a += [key(1.9, g_a + d1), key(2.0, g_a + d1, 1)]
    away = wire(g_a + d1)
    a.append({"time": 2.4, "position": rounded([away[0] + HINGE_DX - 0.03, away[1], away[2] + 0.02])})
    g_b = BETA + math.radians(125) + d1
    wait = wire(g_b)
    wait = rounded([wait[0] + HINGE_DX - 0.03, wait[1], wait[2] + 0.02])
    b = [dict(key(0.0, g_b, 1, True), position=wait), {"time": 1.5, "position": wait},
         key(1.75, g_b), key(1.85, g_b, 0)] + turn(2.1, 3.1, g_b, d2)
    end = wire(g_b + d2)
    end = rounded([end[0] + HINGE_DX, end[1] + PULL_Y, end[2] + PULL_Z])
    b += [{"time": 4.5, "position": end}, {"time": 5.0, "position": end}]
    return a, b


def lip(name, y):
    return f'''    {{
      "name": "{name}",
      "components": [
        // The lip's edge, 4 cm along the wound: the axis of its rounded edge (radius 1 mm, 1 mm inside
        // the cut face and the skin). The cord stands for the strip of tissue a stitch pulls
        // (1000 kg/m³, radius 3 mm: 28 g/m) with soft tissue's modulus.
        {{"type": "DynamicSpline", "control_points": {{"from": [-0.02, {y}, -0.001], "to": [0.02, {y}, -0.001], "count": 8}},
         "radius": 0.003, "density": 1000}},
        {{"type": "GreenLagrangeStretching", "youngs_modulus": 1e5}},
        {{"type": "CurvatureBending", "youngs_modulus": 1e5}},
        // The tissue around it: 3e4 N/m per metre of edge to where it lies, with its viscosity.
        {{"type": "TissueAttachment", "count": 16, "stiffness": 3e4, "damping": 30}},
        // Its rounded edge: the lips meet at their cut faces and press on each other.
        {{"type": "SphereCollisionModel", "radius": 0.001, "self_collision": false}}
      ]
    }}'''


def scene():
    a, b = paths()
    sw = wire(BETA)
    keys = lambda path: ",\n".join("                 " + json.dumps(k) for k in path)
    # The thread leaves the swage along the needle's axis, −T(0) = (sin β, −cos β) in (y, z): the
    # swage's two holds (needle.hpp) start without a pull.
    back = [0.0, math.sin(BETA), -math.cos(BETA)]
    start = f"[0, {sw[1]:.7f}, {sw[2]:.7f}]"
    tail = [sw[i] + LENGTH * back[i] for i in range(3)]
    tail_start = f"[{tail[0]:.7f}, {tail[1]:.7f}, {tail[2]:.7f}]"
    u = [0.0, math.cos(BETA), math.sin(BETA)]
    return f'''// A stitch through a wound (written by apps/tools/make_stitch.py): a 3/8-circle needle (radius 8 mm)
// swaged to 15 cm of 3-0 polypropylene is driven through both lips of a skin incision by two needle
// holders, as a surgeon does. Holder A turns the needle about its centre (the wrist's pronation):
// its tip punctures the left lip's skin 5 mm from the wound, crosses the wound below the skin and
// comes out of the right lip. Holder B takes the needle by its tip side, A lets go, and B turns it
// on until the swage is out, then draws the thread up and away while an assistant holds the tail
// (its end held on a path). Where the tip goes in and comes out, the skin keeps a hole
// (haptics/wound.hpp: a puncture once the tip presses 1 N into it). Once the thread, following the
// needle, runs through a hole, a sliding point holds it there with friction and pulls the lip: four
// holes (into the left lip's skin, out of its cut face, into the right lip's cut face, out of its
// skin). The lips are curves on tissue springs; the taut thread pulls them together until they meet
// (metrics.csv: wound_gap). The thread lies on the skin away from its holes (unilateral contact with
// friction). Real material: the thread's radius 0.1 mm, E = 2 GPa, 910 kg/m³, backward Euler at 1 ms.
{{
  "name": "a stitch through a wound",
  "dt": 1e-3,
  "duration": 5.0,
  "gravity": [0, 0, -9.81],
  "integrator": {{"type": "ImplicitEuler"}},
  "constraint_solver": {{"type": "LagrangeMultiplierSolver"}},
  // The thread on the skin and the lips on each other: unilateral contact with Coulomb friction.
  "collision": {{"type": "ContactPipeline", "response": "unilateral", "friction": 0.3}},
  "output": {{"interval": 0.02, "curve_samples": 64}},
  "camera": {{"position": [0.09, -0.08, 0.07], "look_at": [0.012, 0.0, 0.005], "up": [0, 0, 1],
             "fov": 35, "size": [960, 540], "background": [1, 1, 1]}},
  "nodes": [
    {{
      "name": "suture",
      "components": [
        {{"type": "DynamicSpline", "control_points": {{"from": {start}, "to": {tail_start}, "count": 40}},
         "radius": 1e-4, "density": 910}},
        {{"type": "GreenLagrangeStretching", "youngs_modulus": 2e9}},
        {{"type": "CurvatureBending", "youngs_modulus": 2e9}},
        {{"type": "ViscousDamping", "coefficient": 0.5}},
        {{"type": "SphereCollisionModel", "spacing": 2e-4, "self_collision": false}},
        // The assistant holds the tail's end and brings it towards the wound.
        {{"type": "FixedPointConstraint", "name": "tail held", "abscissa": 1.0, "interpolation": "smooth",
         "path": [{{"time": 0.0, "position": {tail_start}}}, {{"time": 2.5, "position": {json.dumps(TAIL)}}}]}},
        {{"type": "GeneralizedCylinder", "radius": 0.0003, "color": [0.15, 0.25, 0.7]}}
      ]
    }},
{lip("left lip", -0.002)},
{lip("right lip", 0.002)}
  ],
  "needles": [{{"name": "needle", "radius": {R}, "arc": {ARC}, "wire_radius": 2.5e-4,
               "center": [0, 0, {ZC:.7f}], "normal": [1, 0, 0], "start": [0, {u[1]:.7f}, {u[2]:.7f}],
               "thread": "suture", "abscissa": 0.0}}],
  // The skin: 15 mm of each lip beside the wound, 5 mm thick, its edges rounded at 1 mm (the lips'
  // edge curves run 1 mm inside the cut face and the skin); a puncture once the tip has pressed
  // 1 mm into it (1 N at 1000 N/m); up to two holes per lip.
  "wound": {{"lips": ["left lip", "right lip"], "thread": "suture", "normal": [0, 0, 1], "width": 0.015,
            "thickness": 0.005, "edge_radius": 0.001, "puncture_force": 1.0, "indentation_stiffness": 1000,
            "holes_per_lip": 2, "friction": 5e-4}},
  "instruments": [
    {{"name": "holder A", "type": "NeedleHolder", "collide": false,
     "path": [
{keys(a)}]}},
    {{"name": "holder B", "type": "NeedleHolder", "collide": false,
     "path": [
{keys(b)}]}}
  ]
}}
'''


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "scenes"))
    args = parser.parse_args()
    path = os.path.join(args.out, "stitch.json")
    with open(path, "w") as f:
        f.write(scene())
    print(path)


if __name__ == "__main__":
    main()
