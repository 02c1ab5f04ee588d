"""Contact forces and rendered frames as NumPy arrays."""
import numpy as np
import pytest

import filum
from conftest import free_thread

G = 9.81


def thread_on_a_table():
    """The free thread dropped from 5 mm above a table (its axis 6 mm up, radius 1 mm): it falls
    for 32 ms, hits at 0.3 m/s and settles on penalty contacts."""
    document = free_thread(extra=[{"type": "ViscousDamping", "coefficient": 5.0},
                                  {"type": "SphereCollisionModel", "spacing": 1e-3},
                                  {"type": "PlaneObstacle", "name": "table", "point": [0, 0, -6e-3],
                                   "normal": [0, 0, 1]}])
    # Penalty k = 200 N/m, c = 0.01 N·s/m per contact on ~5e-6 kg of thread each: w = 6e3 rad/s
    # (RK4 at 1e-4 s: w dt = 0.6, stable), damping ratio 0.16: settled within a few ms.
    document["collision"] = {"type": "ContactPipeline", "response": "penalty", "stiffness": 200.0, "damping": 0.01}
    return document


def test_contact_forces_carry_the_weight_of_a_thread_at_rest():
    scene = filum.load_dict(thread_on_a_table())
    assert scene.contacts()["force"].shape == (0, 3)          # detection runs in the steps
    scene.run(0.3)
    contacts = scene.contacts()
    k = len(contacts["body"])
    assert k > 10                                            # spheres every 1 mm along 10 cm
    assert contacts["force"].shape == (k, 3) and contacts["point"].shape == (k, 3)
    assert np.all(contacts["obstacle"] == 0) and np.all(contacts["other_body"] == -1)
    assert np.all(contacts["inside_lumen"] == 0)
    assert np.all((contacts["abscissa"] >= 0) & (contacts["abscissa"] <= 1))
    # At rest the table carries the weight: Σ F_z = m g. What is left of the impact at 0.3 s
    # moves at ~0.2 mm/s, and the sphere resampling makes the contact count flicker (101, 102):
    # between 0.15 s and 0.5 s the sum stays within 0.6 % of m g; 2 % leaves room for that and
    # fails a force of the wrong sign, size or count (a missing contact is 1 %, its share of 101).
    weight = scene.bodies[0].mass * G
    assert contacts["force"][:, 2].sum() == pytest.approx(weight, rel=0.02)
    assert np.all(contacts["point"][:, 2] < -4e-3)            # on the table, not where it started
    assert np.all(contacts["force"][:, 2] >= 0.0)            # a table pushes, it never pulls


def wire_in_a_tube():
    """A 0.035" wire (r = 0.445 mm, 4000 kg/m³, 8 cm) on the axis of a level steel tube (lumen
    0.6 mm, 20 cm, clamped at both ends): it comes down onto the lumen's floor."""
    def rod(frm, to, count, radius, density, modulus, extra):
        return [{"type": "FramedChain", "nodes": {"from": frm, "to": to, "count": count},
                 "radius": radius, "density": density},
                {"type": "ChainElasticity", "youngs_modulus": modulus, "poisson_ratio": 0.3},
                {"type": "ViscousDamping", "coefficient": 1.0}] + extra
    tube = rod([0, 0, 0], [0.2, 0, 0], 21, 1e-3, 7900, 2e11,
               [{"type": "ClampConstraint", "abscissa": 0.0}, {"type": "ClampConstraint", "abscissa": 1.0},
                {"type": "SphereCollisionModel", "lumen_radius": 6e-4}])
    wire = rod([0.02, 0, 0], [0.1, 0, 0], 17, 4.45e-4, 4000, 2e9,
               [{"type": "SphereCollisionModel", "inside": "tube"}])
    return {"dt": 1e-3, "gravity": [0, 0, -G], "integrator": {"type": "ImplicitEuler"},
            "constraint_solver": {"type": "LagrangeMultiplierSolver"},
            "collision": {"type": "ContactPipeline", "response": "unilateral"},
            "nodes": [{"name": "tube", "components": tube}, {"name": "wire", "components": wire}]}


def test_a_wire_inside_a_tube_is_held_by_its_lumen():
    scene = filum.load_dict(wire_in_a_tube())
    scene.run(0.3)
    contacts = scene.contacts()
    assert len(contacts["body"]) > 0
    assert np.all(contacts["inside_lumen"] == 1)
    assert np.all(contacts["body"] == 1) and np.all(contacts["other_body"] == 0)
    # At rest on the floor the lumen carries the wire's weight: the wire lands within ~20 ms (it
    # falls 0.155 mm) and its remaining motion, damped at 1/s and by the inelastic contact, changes
    # its momentum by far less than 1e-4 of m g per step after 0.3 s.
    weight = np.pi * 4.45e-4 ** 2 * 0.08 * 4000 * G
    assert contacts["force"][:, 2].sum() == pytest.approx(weight, rel=1e-4)


def test_a_scene_without_collision_has_no_contacts():
    contacts = filum.load_dict(free_thread()).contacts()
    assert contacts["force"].shape == (0, 3)


@pytest.mark.skipif(not filum.rendering_available, reason="this build has no OpenCV (FILUM_WITH_OPENCV=OFF)")
def test_render_draws_the_thread(scenes_dir):
    scene = filum.load(str(scenes_dir / "hanging_thread.json"))
    image = scene.render()
    # The scene's camera: 960 × 540 on a white background, the thread skinned in blue (0.15, 0.3, 0.85).
    assert image.shape == (540, 960, 3) and image.dtype == np.uint8
    white = np.all(image >= 250, axis=2)
    blue = (image[:, :, 2].astype(int) - image[:, :, 0].astype(int)) > 80
    assert white.mean() > 0.5                                # mostly background
    assert blue.sum() > 500                                  # a 10 cm thread, 1.2 mm thick on screen: thousands of pixels
    # After a swing the picture changes where the thread went.
    scene.run(0.2)
    assert np.any(scene.render() != image)
