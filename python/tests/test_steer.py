"""Scripted targets set from Python between steps: a grip steered like a tool."""
import numpy as np
import pytest

import filum
from conftest import free_thread


def held_thread():
    return free_thread(extra=[{"type": "ViscousDamping", "coefficient": 0.5},
                              {"type": "FixedPointConstraint", "name": "grip", "abscissa": 1.0}])


def test_a_steered_grip_carries_the_end_of_the_thread():
    scene = filum.load_dict(held_thread())
    body = scene.body("thread")
    scene.run(0.05)
    start = scene.target("grip")
    np.testing.assert_allclose(start, [0.1, 0.0, 0.0], rtol=0, atol=1e-12)   # held where it started
    u = np.array([0.0, 0.0, 0.2])                                               # lift at 20 cm/s
    scene.steer("grip", start, u)
    t0 = scene.time
    scene.run(0.1)
    expected = start + u * (scene.time - t0)
    np.testing.assert_allclose(scene.target("grip"), expected, rtol=0, atol=1e-15)
    # The rows hold g = P(1) − X(t) with critically damped Baumgarte terms (ω = 0.1/dt = 1000/s):
    # the velocity mismatch −u at the switch decays as u t e^{−ωt}, nothing after 0.1 s; what is
    # left is round-off of coordinates of ~0.1 m (ulp 1.4e-17 m), pulled back every step by the
    # same terms: measured 1.4e-17 m. 1e-14 m allows ~700 ulps; a target the rows did not follow
    # (or followed a step late: 2e-5 m) fails by far.
    np.testing.assert_allclose(body.sample([1.0])[0], expected, rtol=0, atol=1e-14)
    # A second steer stops it where it is.
    scene.steer("grip", scene.target("grip"))
    here = scene.target("grip")
    scene.run(0.05)
    np.testing.assert_allclose(body.sample([1.0])[0], here, rtol=0, atol=1e-14)


def test_steering_names_the_constraints():
    scene = filum.load_dict(held_thread())
    with pytest.raises(KeyError, match="no point constraint named 'needle'; the point constraints are 'grip'"):
        scene.steer("needle", [0, 0, 0])
    with pytest.raises(ValueError, match="finite"):
        scene.steer("grip", [0, 0, float("nan")])


def test_steering_a_grip_that_has_let_go_is_refused():
    # A grip that opens at 0.01 s holds nothing afterwards: steering it would report a target no
    # point follows. Refused with the constraint's name and why; before the release it is accepted.
    scene = filum.load_dict(free_thread(extra=[{"type": "FixedPointConstraint", "name": "grip", "abscissa": 1.0,
                                                "release_at": 0.01}]))
    scene.steer("grip", scene.target("grip"))
    scene.run(0.02)
    with pytest.raises(filum.SceneError, match=r"'grip'.*release_at"):
        scene.steer("grip", [0.2, 0.0, 0.0])
