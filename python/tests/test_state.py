"""The state through NumPy: zero-copy views, writes through the scene, save and restore."""
import numpy as np
import pytest

import filum
from conftest import free_thread


def test_views_share_the_scene_memory_and_follow_the_steps():
    scene = filum.load_dict(free_thread())
    body = scene.body("thread")
    view = body.positions
    assert view.shape == (10, 3)
    assert np.shares_memory(view, scene.q)            # the body's block of the state, not a copy
    before = view[:, 2].copy()
    scene.step()
    assert np.all(view[:, 2] < before)                 # the same view sees the step: it is the state
    with pytest.raises(ValueError):
        view[0, 0] = 1.0                               # read-only: writes go through set_positions


def test_state_round_trip_is_bit_identical():
    scene = filum.load_dict(free_thread(extra=[{"type": "FixedPointConstraint", "abscissa": 0.0}]))
    scene.run(0.005)
    saved = scene.state()
    scene.run(0.005)
    first = np.array(scene.q), np.array(scene.v), scene.time
    scene.set_state(saved)
    assert scene.time == saved.time
    np.testing.assert_array_equal(scene.q, saved.q)
    scene.run(0.005)
    # The step is deterministic (no FMA contraction, no threads): the rerun repeats every bit.
    np.testing.assert_array_equal(scene.q, first[0])
    np.testing.assert_array_equal(scene.v, first[1])
    assert scene.time == first[2]


def test_set_positions_and_velocities_write_the_state():
    scene = filum.load_dict(free_thread(gravity=(0.0, 0.0, 0.0)))
    body = scene.body("thread")
    shifted = body.positions + np.array([0.0, 0.01, 0.0])
    body.set_positions(shifted)
    np.testing.assert_array_equal(body.positions, shifted)
    body.set_velocities(np.tile([0.0, 0.5, 0.0], (body.point_count, 1)))
    scene.run(0.02)
    # A rigid translation at 0.5 m/s without gravity: y = 0.01 + 0.5 t (RK4 exact, round-off only).
    np.testing.assert_allclose(body.positions[:, 1], 0.01 + 0.5 * scene.time, rtol=0, atol=1e-12)


def test_writes_of_the_wrong_shape_name_the_body():
    scene = filum.load_dict(free_thread())
    body = scene.body("thread")
    with pytest.raises(ValueError, match=r"body 'thread' positions: expected an array of shape \(10, 3\), found shape \(9, 3\)"):
        body.set_positions(np.zeros((9, 3)))
    with pytest.raises(ValueError, match="finite"):
        body.set_velocities(np.full((10, 3), np.nan))
    with pytest.raises(KeyError, match="no body at node 'rope'; the bodies are 'thread'"):
        scene.body("rope")
    with pytest.raises(ValueError, match=r"abscissa 1 is 1.5"):
        body.sample([0.5, 1.5])


def test_a_scheduled_refinement_warns_that_views_are_stale():
    document = free_thread()
    document["nodes"][0]["components"][0]["refine"] = [{"time": 0.001, "abscissas": [0.5]}]
    scene = filum.load_dict(document)
    body = scene.body("thread")
    assert body.positions.shape == (10, 3)
    with pytest.warns(RuntimeWarning, match="layout changed"):
        scene.run(0.002)
    assert scene.layout_revision == 1
    assert body.positions.shape == (11, 3)       # taken again: the new layout, one point more
    # Steps that keep the layout say nothing.
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        scene.run(0.001)


def test_a_restored_implicit_run_reruns_bit_for_bit():
    # hanging_thread.json steps implicitly with a factorization kept across steps: the state
    # carries its linearization point and reuse schedule (and the contact warm starts), so the run
    # from a restored state repeats the first one to the bit — saved at 0.5 s, as the user who
    # found 5e-8 m of difference did, and at 1.7 s, where the kept matrix is an old one.
    import conftest
    for save in (0.5, 1.7):
        scene = filum.load(str(conftest.SCENES / "hanging_thread.json"))
        scene.run(save)
        saved = scene.state()
        scene.run(0.1)
        first = np.array(scene.q), np.array(scene.v)
        scene.set_state(saved)
        scene.run(0.1)
        np.testing.assert_array_equal(scene.q, first[0])
        np.testing.assert_array_equal(scene.v, first[1])
