#!/usr/bin/env python3
"""Writes apps/scenes/capstan_held.json and capstan_sliding.json: a silicone cord hanging over a
fixed peg by its own weight, the geometry of tests/collision/capstan_scene.hpp (see there for the
material, the capstan limit and the settling pin released at 0.5 s). Held: the heavy arm at 0.85 of
the limit (the simulated threshold is at 0.93-0.96 of it: this solid cord's bending stiffness,
which the capstan equation leaves out, and the 10 mm spacing cost it a few per cent;
docs/contact-solver.md); sliding:
at 1.2.

    python3 apps/tools/make_capstan.py [--out apps/scenes]
"""
import argparse
import json
import math
import os

PEG_RADIUS, RADIUS, DENSITY, MODULUS, DAMPING = 0.03, 1e-3, 1100.0, 1e6, 5.0
LIGHT_ARM, SPACING, MU = 0.25, 0.01, 0.3


def heaviest_arm(mu, light_arm, wrap_radius):
    """L2_max = e^{μπ} L1 + ρ_c 2μ(1 + e^{μπ})/(1 + μ²) (capstan_scene.hpp)."""
    e = math.exp(mu * math.pi)
    return e * light_arm + wrap_radius * 2 * mu * (1 + e) / (1 + mu * mu)


def control_points(heavy_arm):
    rc = PEG_RADIUS + RADIUS
    arc = math.pi * rc
    length = LIGHT_ARM + arc + heavy_arm
    count = round(length / SPACING) + 1
    step = length / (count - 1)
    bulge = 1 + step * step / (6 * rc * rc)
    points = []
    for i in range(count):
        s = i * step
        if s <= LIGHT_ARM:
            x, z = rc, -(LIGHT_ARM - s)
        elif s <= LIGHT_ARM + arc:
            theta = (s - LIGHT_ARM) / rc
            x, z = bulge * rc * math.cos(theta), bulge * rc * math.sin(theta)
        else:
            x, z = -rc, -(s - LIGHT_ARM - arc)
        points.append([round(x, 9), 0.0, round(z, 9)])
    return points


def scene(name, fraction, duration):
    heavy = fraction * heaviest_arm(MU, LIGHT_ARM, PEG_RADIUS + RADIUS)
    arc = math.pi * (PEG_RADIUS + RADIUS)
    top = (LIGHT_ARM + 0.5 * arc) / (LIGHT_ARM + arc + heavy)
    return {
        "name": name,
        "dt": 1e-3,
        "duration": duration,
        "gravity": [0, 0, -9.81],
        "integrator": {"type": "ImplicitEuler"},
        # Two Gauss-Seidel sweeps before each contact Newton solve: the cord's redundant rows on
        # the peg are released by them instead of one per Newton iteration (docs/contact-solver.md,
        # "A better start").
        "constraint_solver": {"type": "LagrangeMultiplierSolver", "newton_presweeps": 2},
        "collision": {"type": "ContactPipeline", "response": "unilateral"},
        "output": {"interval": 0.01, "curve_samples": 200},
        "camera": {"position": [0.0, -1.2, -0.2], "look_at": [0.0, 0.0, -0.2], "up": [0, 0, 1], "fov": 40,
                   "size": [960, 540], "background": [1, 1, 1]},
        "components": [{"type": "CapsuleObstacle", "name": "peg", "a": [0, -0.05, 0], "b": [0, 0.05, 0],
                        "radius": PEG_RADIUS, "friction": MU}],
        "nodes": [{"name": "cord", "components": [
            {"type": "DynamicSpline", "basis": "uniform_cubic_bspline", "radius": RADIUS, "density": DENSITY,
             "control_points": control_points(heavy)},
            {"type": "GreenLagrangeStretching", "youngs_modulus": MODULUS, "jacobian": "definite"},
            {"type": "ParametricBending", "youngs_modulus": MODULUS},
            {"type": "ViscousDamping", "coefficient": DAMPING},
            {"type": "SphereCollisionModel", "spacing": 2 * RADIUS},
            {"type": "FixedPointConstraint", "name": "settling pin", "abscissa": round(top, 12), "release_at": 0.5},
            {"type": "GeneralizedCylinder", "radius": RADIUS}]}],
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--out", default=os.path.join(os.path.dirname(__file__), "..", "scenes"))
    args = parser.parse_args()
    for name, fraction in (("capstan_held", 0.85), ("capstan_sliding", 1.2)):
        path = os.path.join(args.out, name + ".json")
        with open(path, "w") as f:
            f.write("// A silicone cord over a fixed steel peg by its own weight (mu = %g), heavy arm at %g of the\n"
                    "// capstan limit: %s. Written by apps/tools/make_capstan.py; the physics is in\n"
                    "// tests/collision/capstan_scene.hpp.\n" % (MU, fraction, "it holds" if fraction < 1 else "it slides"))
            json.dump(scene(name.replace("_", " "), fraction, 2.0 if fraction < 1 else 1.5), f, indent=1)
            f.write("\n")
        print("wrote", path)


if __name__ == "__main__":
    main()
