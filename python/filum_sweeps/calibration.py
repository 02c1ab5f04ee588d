"""Material calibration against a measured curve, one candidate per task.

The model: a strip of silicone tubing (r = 1 mm, 1150 kg/m³, 5 cm) clamped horizontally at one end
and sagging under gravity; its rest shape depends on Young's modulus E through the bending
stiffness EI (a linear cantilever sags q L⁴ / 8EI: 3.5 mm at E = 10 MPa). Each task loads the
scene with one E through the Python module, lets it settle and returns the RMS distance of its
curve P(s) to the measured points at the same abscissas; the calibrated E is the grid's best.
Unlike the C++ studies, the tasks run the `filum` module in the worker itself (its steps release
the GIL, so the threads of a LocalCluster run them in parallel).
"""
import functools

import numpy as np

from .engine import map_tasks

LENGTH = 0.05          # m
SETTLE_TIME = 1.0      # s: with viscous γ = 60/s the slowest mode (ω ≈ 46 rad/s at 5 MPa) is
                       # overdamped-to-critical and has decayed by e^{-30} (speeds ~1e-13 m/s)


def strip_scene(youngs_modulus, control_points=12):
    """The clamped strip as a scene dict (linearized backward Euler at 1 ms)."""
    return {
        "name": f"strip E={youngs_modulus:g}", "dt": 1e-3, "gravity": [0, 0, -9.81],
        "integrator": {"type": "ImplicitEuler"},
        "nodes": [{"name": "strip", "components": [
            {"type": "DynamicSpline",
             "control_points": {"from": [0, 0, 0], "to": [LENGTH, 0, 0], "count": control_points},
             "radius": 1e-3, "density": 1150.0},
            {"type": "GreenLagrangeStretching", "youngs_modulus": youngs_modulus},
            {"type": "ParametricBending", "youngs_modulus": youngs_modulus},
            {"type": "ViscousDamping", "coefficient": 60.0},
            {"type": "ClampConstraint", "abscissa": 0.0}]}],
    }


def rest_curve(youngs_modulus, abscissas):
    """P(s) of the settled strip at the abscissas (m, len(abscissas) × 3)."""
    import filum  # on the worker: the module is found through its PYTHONPATH

    scene = filum.load_dict(strip_scene(youngs_modulus), source=f"calibration E={youngs_modulus:g}")
    scene.run(SETTLE_TIME)
    return scene.body("strip").sample(list(abscissas))


def misfit(youngs_modulus, abscissas, measured):
    """RMS distance (m) between the model's rest curve at E and the measured points."""
    difference = rest_curve(youngs_modulus, abscissas) - np.asarray(measured, dtype=float)
    return float(np.sqrt(np.mean(np.sum(difference ** 2, axis=1))))


def calibrate(abscissas, measured, moduli, client=None):
    """Misfit of every candidate modulus, through the client's workers (serially without one).

    Returns (best modulus, [(modulus, misfit), ...] in the order of `moduli`)."""
    task = functools.partial(misfit, abscissas=list(abscissas), measured=np.asarray(measured).tolist())
    misfits = map_tasks(task, list(moduli), client, key_prefix="calibration")
    table = list(zip(moduli, misfits))
    return min(table, key=lambda row: row[1])[0], table
