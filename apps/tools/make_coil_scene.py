#!/usr/bin/env python3
"""Writes apps/scenes/coil_in_sac.json: a detachable platinum coil in the sac of the cerebral aneurysm of
apps/scenes/data/cerebral_aneurysm.json, laid in its helical rest shape (docs/vessels.md, "The coil").

The coil is a "10 system" coil: a platinum wire (coils are often of a platinum-tungsten
alloy, which is stiffer; pure platinum's constants are used here) of diameter d = 50 um wound into a primary
coil of outer diameter 0.254 mm (0.010"), mean winding diameter D = 0.204 mm, close wound (pitch d).
As a rod (r = 0.127 mm) it has the stiffness of the winding, not of solid platinum. A bending moment
M on the primary coil bends and twists the wire: per turn (length d) the wire stores
M^2 pi D / 4 (1/(E I_w) + 1/(G J_w)), I_w = pi d^4 / 64, J_w = 2 I_w, so
    E I = d^5 / (32 D (1/E + 1/(2G)))  = 3.4e-9 N m^2   (E = 168 GPa, G = 61 GPa: platinum),
an effective Young's modulus E I / (pi r^4 / 4) = 16.6 MPa over the rod's section; a twisting
moment bends the wire only, G J = E d^5 / (64 D), 1.2 E I: Poisson's ratio 0 (G J = E I) is the
nearest the rod takes. Density: the wire's volume per length, pi^2 D d / 4, over pi r^2, times
21450 kg/m^3: 10654 kg/m^3.
The secondary shape, the one the coil takes once out of the microcatheter: a helix of radius 3 mm
(a 6 mm coil) and pitch 0.4 mm, 6 cm long, laid in the sac around an axis along y (the patient's
front-back axis; gravity points to the back, +y).

Run from anywhere: python3 apps/tools/make_coil_scene.py
"""
import json
import math
import os
import re

HERE = os.path.dirname(os.path.abspath(__file__))
SCENE = os.path.join(HERE, "..", "scenes", "coil_in_sac.json")

WIRE_D, WINDING_D = 50e-6, 0.204e-3
E_PT, G_PT, RHO_PT = 168e9, 61e9, 21450.0
RADIUS = 0.127e-3
EI = WIRE_D**5 / (32 * WINDING_D * (1 / E_PT + 1 / (2 * G_PT)))
E_EFF = EI / (math.pi * RADIUS**4 / 4)
RHO_EFF = RHO_PT * (math.pi**2 * WINDING_D * WIRE_D / 4) / (math.pi * RADIUS**2)
HELIX_R, PITCH, LENGTH, NODES = 3e-3, 0.4e-3, 0.06, 121
SAC_CENTRE = (0.0, 0.0, 0.015)  # m, data/cerebral_aneurysm.json's dome


def helix():
    c = PITCH / (2 * math.pi)
    turn = LENGTH / math.hypot(HELIX_R, c)  # rad of the helix for the coil's length
    points = []
    for k in range(NODES):
        t = turn * k / (NODES - 1)
        points.append([round(SAC_CENTRE[0] + HELIX_R * math.cos(t), 8),
                       round(SAC_CENTRE[1] + c * (t - 0.5 * turn), 8),
                       round(SAC_CENTRE[2] + HELIX_R * math.sin(t), 8)])
    return points


HEADER = """// A detachable platinum coil in a cerebral aneurysm's sac: the framing coil of an endovascular
// coiling, laid in its helical rest shape in the dome and let go. It settles onto the dome's wall
// under its weight (the patient is supine: gravity to the back, +y), held there with friction; the
// run reports the sac's packing density (metrics.json, "aneurysm").
// The vessel (data/cerebral_aneurysm.json): a cerebral artery's C-bend (radius 2 mm) with a
// saccular aneurysm on its outer side, neck 4 mm, dome 8 mm across, touched from inside.
// The coil (apps/tools/make_coil_scene.py writes this file and derives the numbers): a "10
// system" coil, a 50 um platinum wire wound into a 0.254 mm primary coil, as a rod of
// r = 0.127 mm with the winding's bending stiffness E I = %.2e N m^2 (an effective E of %.3g MPa
// over the rod's section, Poisson's ratio 0) and density %.0f kg/m^3; its secondary shape a helix
// 6 mm across with a 0.4 mm pitch, 6 cm long: a discrete Cosserat rod of %d nodes (0.5 mm), rest
// shape the initial one, stepped implicitly at 1 ms. Blood's drag as a viscous damping of 5/s.
// Not in this scene: the microcatheter and the pushing of the coil out of it (coil.json does that;
// docs/vessels.md, "The coil pushed out of a microcatheter").
"""


def scene():
    return {
        "name": "coil in a cerebral aneurysm",
        "dt": 1e-3,
        "duration": 1.0,
        "gravity": [0, 9.81, 0],
        "integrator": {"type": "ImplicitEuler"},
        "constraint_solver": {"type": "LagrangeMultiplierSolver"},
        "collision": {"type": "ContactPipeline", "response": "unilateral", "friction": 0.1},
        "output": {"interval": 0.02, "curve_samples": 400},
        # Close on the dome from the front and a little above, through the translucent wall.
        "camera": {"position": [0.006, -0.024, 0.024], "look_at": [0.0, 0.001, 0.013], "up": [0, 0, 1],
                   "fov": 40, "size": [720, 720], "background": [1, 1, 1]},
        "fluoroscopy": {"lao": 0, "cranial": 0, "isocenter": [0.0, 0.0, 0.01], "field": 0.05},
        "navigation": {"vessels": "vessels",
                       "aneurysm": {"branches": ["neck", "sac"], "coils": ["coil"]}},
        "nodes": [
            {"name": "vessels", "components": [
                {"type": "VesselLumenObstacle", "file": "data/cerebral_aneurysm.json", "friction": 0.1},
                {"type": "VesselLumenModel", "file": "data/cerebral_aneurysm.json"}]},
            {"name": "coil", "components": [
                {"type": "FramedChain", "nodes": helix(), "radius": RADIUS, "density": round(RHO_EFF)},
                {"type": "ChainElasticity", "youngs_modulus": float("%.3g" % E_EFF), "poisson_ratio": 0.0,
                 "rest_shape": "initial"},
                {"type": "ViscousDamping", "coefficient": 5.0},
                {"type": "SphereCollisionModel", "spacing": 2.5e-4},
                {"type": "GeneralizedCylinder", "radius": RADIUS, "color": [0.3, 0.3, 0.36]}]},
        ],
    }


def write():
    # Lists of numbers on one line (a node, a colour), so that the node list is one node per line.
    text = re.sub(r"\[\s*([-+0-9.e,\s]+?)\s*\]",
                  lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]",
                  json.dumps(scene(), indent=2))
    with open(SCENE, "w") as out:
        out.write(HEADER % (EI, E_EFF / 1e6, RHO_EFF, NODES))
        out.write(text + "\n")
    print("wrote", SCENE)


if __name__ == "__main__":
    write()
