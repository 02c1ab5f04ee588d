"""Scene errors reach Python as filum.SceneError with the place of the fault."""
import math

import pytest

import filum
from conftest import free_thread


def test_negative_density_names_the_json_path():
    document = free_thread()
    document["nodes"][0]["components"][0]["density"] = -1.0
    with pytest.raises(filum.SceneError, match=r"my scene: /nodes/0/components/0/density"):
        filum.load_dict(document, source="my scene")


def test_nan_from_python_is_refused_at_its_path():
    document = free_thread()
    document["gravity"] = [0.0, 0.0, math.nan]
    with pytest.raises(filum.SceneError, match=r"<dict>: /gravity"):
        filum.load_dict(document)


def test_unknown_type_lists_the_known_ones():
    document = free_thread(extra=[{"type": "Stifness"}])
    with pytest.raises(filum.SceneError) as error:
        filum.load_dict(document)
    assert "/nodes/0/components/3/type" in str(error.value)
    assert "GreenLagrangeStretching" in str(error.value)


def test_a_missing_file_is_named(tmp_path):
    with pytest.raises(filum.SceneError, match="nowhere.json"):
        filum.load(str(tmp_path / "nowhere.json"))


def test_a_value_json_cannot_hold_is_refused_with_its_path():
    document = free_thread()
    document["nodes"][0]["components"][0]["radius"] = object()
    with pytest.raises(TypeError, match=r"<dict>: /nodes/0/components/0/radius"):
        filum.load_dict(document)


def test_scene_files_load_and_step(scenes_dir):
    scene = filum.load(scenes_dir / "hanging_thread.json")        # a pathlib.Path or a str
    assert scene.name == "hanging thread"
    scene.step()
    assert scene.step_count == 1
    assert scene.time == scene.dt


def test_a_diverging_step_raises_step_error_and_rolls_back():
    # Explicit Euler at 10 ms on this thread's ~7e3 rad/s axial mode: each step multiplies an
    # undamped oscillation by |1 + i w dt| = 70, so it exceeds max_speed within a few steps.
    scene = filum.load_dict(free_thread(dt=1e-2, integrator="ExplicitEuler",
                                        extra=[{"type": "FixedPointConstraint", "abscissa": 0.0}]))
    with pytest.raises(filum.StepError, match=r"step \d+ at t = .* failed .*back at the state before that step"):
        scene.run(10.0)
    assert scene.q.size and all(abs(x) < 1e3 for x in scene.q)   # the last good state, finite
    assert scene.time == scene.step_count * scene.dt
