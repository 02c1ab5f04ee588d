#!/usr/bin/env python3
"""Writes apps/scenes/coil.json: the coil of coil_in_sac.json (apps/tools/make_coil_scene.py derives
its material) pushed out of a microcatheter into the sac of the cerebral aneurysm of
apps/scenes/data/cerebral_aneurysm.json, where it takes its helical secondary shape and curls up
against the dome and itself (docs/vessels.md, "The coil pushed out of a microcatheter").

The microcatheter: a ChannelConstraint centre line (the coil's axis follows it while inside: the
coil's 0.254 mm in the 0.42 mm lumen of a "10 system" microcatheter, 83 um of play neglected) and
its wall drawn as a tube of 0.3 mm (a 1.7 F microcatheter). Its path, in the vessel's plane (y = 0):
up the parent's inlet along x = 8 mm, round the C-bend on its centreline (radius 8 mm about the
origin) to the heading psi_1, then back through a steam-shaped tip of bend radius RB into the neck,
ending on the neck's axis (x = 0) pointing into the dome. Ending at x = 0 fixes psi_1:
    8 cos psi_1 - RB (1 - cos psi_1) = 0,   cos psi_1 = RB / (8 + RB).
Below the inlet it goes straight on, long enough to hold the whole coil at the start.

The coil starts straight in the channel, its distal end START_BEHIND inside the tip, with the
helix's rest curvature and twist (not its shape): a helix of radius R and pitch p has curvature
R / (R^2 + c^2) and torsion c / (R^2 + c^2), c = p / 2 pi. The delivery wire holds the coil's
proximal end (FixedPointConstraint on a path) and pushes it at PUSH_SPEED up the channel until
that end is DETACH_BEHIND from the tip, where the coil is detached (released); the run goes on 1 s.
Run from anywhere: python3 apps/tools/make_coil_delivery_scene.py
"""
import json
import math
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import make_coil_scene as coil  # noqa: E402  (the coil's material, derived there)
# Nodes every 0.25 mm, half coil_in_sac.json's spacing: at 0.5 mm the coil turns by 0.17 rad per node,
# and the node between the last one held and the tip support was flung out of the tip within the
# first 60 ms (the run diverged); at 0.25 mm (0.083 rad per node) the whole delivery runs.
NODES = 2 * (coil.NODES - 1) + 1

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "coil.json")

BEND, RB = 8e-3, 2e-3           # m: the C-bend's centreline radius (the vessel data), the tip's bend radius
TIP_Z = 10.0e-3                 # m: the microcatheter's tip on the neck's axis (neck 8 to 10.5 mm)
INLET_Z = -10e-3                # m: the parent's inlet (the vessel data)
STEP = 2.5e-4                   # m: the channel's polyline spacing (a 2 mm bend turns 7 degrees per segment)
CATHETER_RADIUS = 0.3e-3        # m: 1.7 F
PUSH_SPEED = 0.02               # m/s
# Detached with its proximal end three node spacings behind the tip, as soon as it is there: the
# channel holds a node only while it is a spacing or more behind the tip, so pushed on, the coil
# was held in the end by the delivery wire's point alone, pivoted about it, and the run diverged
# (at 3.03 s, with its end 0.46 mm behind the tip). Once detached its tail is free to slide out.
DETACH_BEHIND = 3 * coil.LENGTH / (NODES - 1)  # m: 0.75 mm
# The channel's rows hold each node to the centre line at the acceleration level without the
# centripetal v^2 / R of a node sliding round a bend, which the stabilization balances at an offset
# v^2 / (R omega^2); at the contact rows' rate 0.5/dt that is 0.8 um in the tip's bend (20 um at the
# default 0.1/dt).
CHANNEL_OMEGA = 500.0           # 1/s
START_BEHIND = 1e-3             # m: the coil's distal end starts this far inside the tip


def channel():
    """The microcatheter's centre line from proximal to tip (m), every STEP or finer."""
    psi1 = math.acos(RB / (BEND + RB))
    points = []
    # Straight up x = BEND to z = 0, from far enough below to hold the whole coil and 5 mm more.
    above = (BEND + RB) * psi1 + (TIP_Z - (BEND + RB) * math.sin(psi1))  # the channel's length above z = 0
    bottom = min(-(coil.LENGTH + 5e-3 - above), INLET_Z - 2e-3)
    n = max(1, int(math.ceil((0.0 - bottom) / STEP)))
    for k in range(n):
        points.append([BEND, 0.0, bottom + (0.0 - bottom) * k / n])
    # Round the bend: heading psi from +z towards -x, at radius BEND about the origin.
    n = max(1, int(math.ceil(BEND * psi1 / STEP)))
    for k in range(n):
        psi = psi1 * k / n
        points.append([BEND * math.cos(psi), 0.0, BEND * math.sin(psi)])
    # The tip's bend back to +z, radius RB: centre at distance BEND + RB from the origin.
    centre = ((BEND + RB) * math.cos(psi1), (BEND + RB) * math.sin(psi1))
    n = max(1, int(math.ceil(RB * psi1 / STEP)))
    for k in range(n):
        psi = psi1 * (1 - k / n)
        points.append([centre[0] - RB * math.cos(psi), 0.0, centre[1] - RB * math.sin(psi)])
    start = (centre[0] - RB, centre[1])  # psi = 0: on the neck's axis, heading +z
    n = max(1, int(math.ceil((TIP_Z - start[1]) / STEP)))
    for k in range(n + 1):
        points.append([start[0], 0.0, start[1] + (TIP_Z - start[1]) * k / n])
    return [[round(c, 9) for c in p] for p in points]


def arc_lengths(points):
    s = [0.0]
    for a, b in zip(points, points[1:]):
        s.append(s[-1] + math.dist(a, b))
    return s


def point_at(points, s_table, s):
    for i in range(1, len(points)):
        if s_table[i] >= s:
            t = (s - s_table[i - 1]) / (s_table[i] - s_table[i - 1])
            return [points[i - 1][j] + t * (points[i][j] - points[i - 1][j]) for j in range(3)]
    return points[-1]


def scene():
    path = channel()
    s_table = arc_lengths(path)
    total = s_table[-1]
    start = total - coil.LENGTH - START_BEHIND  # the coil's proximal end along the channel
    nodes = [[round(c, 9) for c in point_at(path, s_table, start + coil.LENGTH * k / (NODES - 1))]
             for k in range(NODES)]
    c = coil.PITCH / (2 * math.pi)
    kappa = coil.HELIX_R / (coil.HELIX_R**2 + c**2)
    tau = c / (coil.HELIX_R**2 + c**2)
    # The pusher: the proximal end from where it starts, along the channel, to DETACH_BEHIND from the
    # tip, at PUSH_SPEED,
    # with a key at every vertex of the centre line it passes (keys farther apart would cut across
    # the tip's bend, by 0.14 mm at 1.5 mm apart, and kink the coil against its first point held).
    push_time = (coil.LENGTH + START_BEHIND - DETACH_BEHIND) / PUSH_SPEED
    end = total - DETACH_BEHIND
    arcs = [start] + [a for a in s_table if start < a < end] + [end]
    pusher = [{"time": round((a - start) / PUSH_SPEED, 6),
               "position": [round(v, 9) for v in point_at(path, s_table, a)]} for a in arcs]
    detach = round(push_time, 6)
    tube = {"units": "m", "blend": 1.0,
            "branches": [{"name": "microcatheter", "open": ["start", "end"],
                          "points": [p + [CATHETER_RADIUS] for p in path[::4] + ([path[-1]] if (len(path) - 1) % 4 else [])]}]}
    # coil_in_sac.json's scene (vessels, contact, metrics, the coil's collision and visual models),
    # with the microcatheter added and the coil straight in it with its helix's rest curvature.
    data = coil.scene()
    data.update({
        "name": "coil pushed out of a microcatheter into a cerebral aneurysm",
        "duration": round(detach + 1.0, 6),
        "output": {"interval": 0.05, "curve_samples": 400},
        "camera": {"position": [0.006, -0.03, 0.02], "look_at": [0.0, 0.0, 0.011], "up": [0, 0, 1],
                   "fov": 40, "size": [720, 720], "background": [1, 1, 1]},
        "fluoroscopy": {"lao": 0, "cranial": 0, "isocenter": [0.0, 0.0, 0.008], "field": 0.05},
    })
    data["nodes"].insert(1, {"name": "microcatheter", "components": [
        {"type": "VesselLumenModel", **tube, "color": [0.85, 0.85, 0.8], "opacity": 0.5}]})
    laid = data["nodes"][2]["components"]  # FramedChain, ChainElasticity, ViscousDamping, spheres, skin
    assert [c["type"] for c in laid] == ["FramedChain", "ChainElasticity", "ViscousDamping",
                                         "SphereCollisionModel", "GeneralizedCylinder"]
    laid[0]["nodes"] = nodes
    laid[1].pop("rest_shape")
    laid[1].update({"rest_curvature": [round(kappa, 4), 0.0], "rest_twist": round(tau, 4)})
    data["nodes"][2]["components"] = laid[:3] + [
        {"type": "FixedPointConstraint", "name": "delivery wire", "abscissa": 0.0, "path": pusher,
         "release_at": detach},
        {"type": "ChannelConstraint", "centre_line": path, "stabilization": CHANNEL_OMEGA}] + laid[3:]
    return data

HEADER = """// A detachable platinum coil pushed out of a microcatheter into a cerebral aneurysm's sac, where it
// takes its helical secondary shape and curls up against the dome and itself; the packing density
// of the sac grows as it goes in (metrics.csv, packing_density). Written by
// apps/tools/make_coil_delivery_scene.py, which derives the numbers (the coil's material: coil_in_sac.json).
// The microcatheter is a channel the coil's centre line follows while inside (ChannelConstraint):
// up the parent artery, round its C-bend, and through a steam-shaped tip into the neck. The
// delivery wire (a FixedPointConstraint on a path) pushes the coil's proximal end at %.0f mm/s to
// 0.75 mm behind the tip, where the coil is detached, at t = %.2f s.
"""


def write():
    text = re.sub(r"\[\s*([-+0-9.e,\s]+?)\s*\]",
                  lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]",
                  json.dumps(scene(), indent=2))
    data = scene()
    with open(SCENE, "w") as out:
        out.write(HEADER % (PUSH_SPEED * 1e3, data["nodes"][2]["components"][3]["release_at"]))
        out.write(text + "\n")
    print("wrote", SCENE)


if __name__ == "__main__":
    write()
