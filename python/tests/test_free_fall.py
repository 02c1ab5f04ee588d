"""Free fall through the Python module: the physics, not only that it runs."""
import numpy as np
import pytest

import filum
from conftest import free_thread

G = 9.81


def test_free_fall_matches_g_t2_over_2():
    scene = filum.load_dict(free_thread())
    body = scene.body("thread")
    q0 = np.array(body.positions)              # a copy: body.positions is a live view
    steps = scene.run(0.2)
    assert steps == 2000
    t = scene.time
    assert t == steps * scene.dt                  # time is steps × dt, no running sum
    expected_drop = 0.5 * G * t * t               # 0.196 m
    displacement = body.positions - q0
    # RK4 integrates a constant acceleration exactly, and a rigidly translated thread has no elastic
    # force but round-off: strains from coordinates of ~0.1 m over 14 mm spans carry ~ulp(0.2)/1.4e-2
    # = 2e-15, times EA = 9.4 N, ~2e-14 N on control points of ~4e-5 kg: 5e-10 m/s² of spurious
    # acceleration at most, 1e-10 m/s and 1e-11 m over 0.2 s even if every step added up (observed:
    # 6e-15 m, 3e-13 m/s). A wrong factor (t² for t²/2, one step more: 2e-5 m) fails by far.
    np.testing.assert_allclose(displacement[:, 2], -expected_drop, rtol=0, atol=1e-11)
    np.testing.assert_allclose(displacement[:, :2], 0.0, rtol=0, atol=1e-11)
    np.testing.assert_allclose(body.velocities[:, 2], -G * t, rtol=0, atol=1e-10)
    # P(s) falls with the control points: the curve is Σ b_i(s) q_i and Σ b_i = 1.
    s = np.linspace(0.0, 1.0, 11)
    samples = body.sample(s)
    np.testing.assert_allclose(samples[:, 0], 0.1 * s, rtol=0, atol=1e-11)
    np.testing.assert_allclose(samples[:, 2], -expected_drop, rtol=0, atol=1e-11)
    np.testing.assert_allclose(body.sample_velocity(s)[:, 2], -G * t, rtol=0, atol=1e-10)


def test_energy_is_conserved_in_free_fall():
    scene = filum.load_dict(free_thread())
    e0 = scene.energy()["total"]
    scene.run(0.1)
    e = scene.energy()
    # Kinetic energy m (g t)²/2 = 1.7e-4 J for 3.6 g at t = 0.1 s, exactly what gravity's potential
    # lost: RK4 is exact here, what is left is round-off of J-sized sums (1e-15 relative).
    mass = scene.bodies[0].mass
    np.testing.assert_allclose(e["kinetic"], 0.5 * mass * (G * 0.1) ** 2, rtol=1e-9)
    assert abs(e["total"] - e0) <= 1e-9 * e["kinetic"]


def test_timing_counts_the_steps():
    scene = filum.load_dict(free_thread())
    scene.run(0.01)
    timing = scene.timing
    assert timing["steps"] == 100
    assert timing["wall_s"] > 0.0
    assert timing["max_step_s"] >= timing["mean_step_s"] > 0.0
    # simulated / wall: 100 steps of 1e-4 s (products of doubles: relative round-off only).
    assert timing["real_time_factor"] == pytest.approx(0.01 / timing["wall_s"], rel=1e-12)
