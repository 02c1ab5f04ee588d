"""Shared scenes of the Python tests (python/tests/, ctest label python).

ctest sets PYTHONPATH to build/python (the module) and python/ (filum_sweeps), and
FILUM_SOURCE_DIR / FILUM_BINARY_DIR to the tree and the build.
"""
import os
import pathlib

import pytest

SOURCE_DIR = pathlib.Path(os.environ.get("FILUM_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
BINARY_DIR = pathlib.Path(os.environ.get("FILUM_BINARY_DIR", SOURCE_DIR / "build"))
SCENES = SOURCE_DIR / "apps" / "scenes"


def free_thread(count=10, length=0.1, gravity=(0.0, 0.0, -9.81), dt=1e-4, integrator="RungeKutta4", extra=()):
    """A free silicone vessel loop (r = 1 mm, E = 3 MPa, 1150 kg/m³) straight along x, as a dict.

    Its stiffest axial mode on `count` control points has w ~ 2 sqrt(E/rho) / h (h = length /
    (count - 3)): for 10 points about 7e3 rad/s, so RK4 (stable below 2.8 / w = 4e-4 s) runs at
    dt = 1e-4 s.
    """
    return {
        "name": "free thread",
        "dt": dt,
        "duration": 0.2,
        "gravity": list(gravity),
        "integrator": {"type": integrator},
        "nodes": [{
            "name": "thread",
            "components": [
                {"type": "DynamicSpline", "basis": "uniform_cubic_bspline",
                 "control_points": {"from": [0.0, 0.0, 0.0], "to": [length, 0.0, 0.0], "count": count},
                 "radius": 1e-3, "density": 1150.0},
                {"type": "GreenLagrangeStretching", "youngs_modulus": 3e6},
                {"type": "ParametricBending", "youngs_modulus": 3e6},
                *extra,
            ],
        }],
    }


@pytest.fixture
def scenes_dir():
    return SCENES
