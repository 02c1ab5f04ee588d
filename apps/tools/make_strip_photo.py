#!/usr/bin/env python3
"""Writes docs/data/strip_photo.csv, the "measured" curve of the calibration example of
docs/sweeps.md. It is SYNTHETIC, not a measurement: a stand-in for points picked on a photo of a
clamped strip of silicone tubing sagging under gravity, made by filum itself.

The truth: the strip of filum_sweeps/calibration.py (r = 1 mm, 1150 kg/m³, 5 cm, clamped
horizontally at s = 0) at Young's modulus E = 6 MPa, settled as calibrate() settles it, but on
40 control points instead of the 12 that calibrate() fits with (the "photo" is not the fitted
model itself). Its points P(s) at the 11 abscissas s = 0, 0.1, ..., 1, in metres in the model's
frame (x along the clamp, z up), each coordinate with Gaussian noise of 25 µm (a pixel of a
2000-pixel-wide photo of the 5 cm strip; generator seed 34), rounded to 1 µm: 11 rows x,y,z.

    PYTHONPATH=build/python:python /usr/bin/python3 apps/tools/make_strip_photo.py [--out FILE]

The result depends only on the build's arithmetic (the same file from the same build); the
calibration of docs/sweeps.md then finds E within a grid step of 6 MPa.
"""
import argparse
import os
import sys

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
TREE = os.path.normpath(os.path.join(HERE, "..", ".."))
# The module and filum_sweeps, when PYTHONPATH does not name them.
sys.path[:0] = [os.path.join(os.environ.get("FILUM_BINARY_DIR", os.path.join(TREE, "build")), "python"),
                os.path.join(TREE, "python")]

import filum  # noqa: E402
from filum_sweeps.calibration import SETTLE_TIME, strip_scene  # noqa: E402

TRUE_MODULUS = 6e6       # Pa
CONTROL_POINTS = 40      # the fit uses 12
NOISE = 25e-6            # m, standard deviation of each coordinate
SEED = 34
ABSCISSAS = np.linspace(0.0, 1.0, 11)


def photo():
    """The 11 × 3 synthetic measured points (m)."""
    scene = filum.load_dict(strip_scene(TRUE_MODULUS, control_points=CONTROL_POINTS), source="strip photo")
    scene.run(SETTLE_TIME)
    curve = scene.body("strip").sample(list(ABSCISSAS))
    noisy = curve + np.random.default_rng(SEED).normal(0.0, NOISE, curve.shape)
    return np.round(noisy, 6)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", default=os.path.join(TREE, "docs", "data", "strip_photo.csv"))
    args = parser.parse_args()
    header = (f"SYNTHETIC, not measured: filum's clamped strip at E = {TRUE_MODULUS:g} Pa on {CONTROL_POINTS} control points,\n"
              f"with {NOISE * 1e6:g} um of Gaussian noise (seed {SEED}): apps/tools/make_strip_photo.py.\n"
              "P(s) at s = 0, 0.1, ..., 1: x,y,z (m)")
    np.savetxt(args.out, photo(), fmt="%.6f", delimiter=",", header=header)
    print(f"wrote {args.out}")


if __name__ == "__main__":
    main()
