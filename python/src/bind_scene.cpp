// filum.Scene: load (file or dict), step, run, the state as views or copies, energies, contact
// forces, a rendered frame, the timing of the steps.
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/sphere_collision_model.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_loader.hpp"
#include "json_from_python.hpp"

namespace filum::python {

namespace {

/// The contacts of the last step's detection as arrays (copies): for contact i, the body index
/// and abscissa of thread point A, its position P_A (m), the force on A (N: the penalty, or the
/// unilateral multipliers of the last solve), the obstacle index (−1: thread–thread) and the other
/// thread's body (−1: obstacle), and whether A is held inside the lumen of that body (coaxial
/// instruments). Empty arrays when the scene has no collision pipeline.
py::dict contacts(const PythonScene& owner) {
  const Scene& scene = owner.scene();
  const auto* pipeline = dynamic_cast<const collision::ContactPipeline*>(scene.collisionPipeline());
  const int k = pipeline ? static_cast<int>(pipeline->contacts().size()) : 0;
  Eigen::VectorXi body(k), other(k), obstacle(k), lumen(k);
  VecX abscissa(k);
  Points point(k, 3), force(k, 3);
  auto bodyIndex = [&](int model) {
    const CurveBody* curve = &pipeline->models()[model]->curve();
    for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b)
      if (scene.bodies()[b]->curve() == curve) return b;
    return -1;
  };
  for (int i = 0; i < k; ++i) {
    const collision::Contact& c = pipeline->contacts()[i];
    body[i] = bodyIndex(c.model_a);
    other[i] = c.model_b >= 0 ? bodyIndex(c.model_b) : -1;
    obstacle[i] = c.obstacle;
    lumen[i] = c.insideLumen() ? 1 : 0;
    abscissa[i] = c.a.abscissa();
    point.row(i) = pipeline->models()[c.model_a]->curve().position(scene.state().q, c.a.abscissa()).transpose();
    force.row(i) = pipeline->contactForce(i, scene.state()).transpose();
  }
  py::dict out;
  out["body"] = body;
  out["abscissa"] = abscissa;
  out["point"] = point;
  out["force"] = force;
  out["obstacle"] = obstacle;
  out["other_body"] = other;
  out["inside_lumen"] = lumen;
  return out;
}

/// The frame as an H × W × 3 RGB array (a copy: the renderer's image is BGR).
py::array_t<std::uint8_t> renderFrame(PythonScene& owner) {
  const visual::Image image = owner.render();
  py::array_t<std::uint8_t> rgb({static_cast<py::ssize_t>(image.height), static_cast<py::ssize_t>(image.width),
                                 py::ssize_t{3}});
  auto out = rgb.mutable_unchecked<3>();
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const auto bgr = image.at(x, y);
      for (int c = 0; c < 3; ++c) out(y, x, c) = bgr[2 - c];
    }
  return rgb;
}

/// The point constraint named `name` (its "name" in the scene); KeyError listing the named ones.
constraints::TargetConstraint& targetConstraint(const PythonScene& owner, const std::string& name) {
  std::string known;
  for (Constraint* c : owner.scene().constraints()) {
    auto* t = dynamic_cast<constraints::TargetConstraint*>(c);
    if (!t) continue;
    if (c->name() == name) return *t;
    known += (known.empty() ? "'" : ", '") + c->name() + "'";
  }
  throw py::key_error("no point constraint named '" + name + "'; the point constraints are " +
                      (known.empty() ? "none" : known));
}

/// Moves the target of constraint `name` from now on: X(t) = position + velocity (t − now).
void steer(PythonScene& owner, const std::string& name, const Vec3& position, const Vec3& velocity) {
  if (!position.allFinite() || !velocity.allFinite())
    throw py::value_error("steer('" + name + "'): expected finite position and velocity");
  targetConstraint(owner, name);  // KeyError listing the point constraints
  for (Constraint* c : owner.scene().constraints())
    if (c->name() == name && dynamic_cast<constraints::TargetConstraint*>(c))
      return constraints::steerTarget(*c, owner.scene().state(), position, velocity);  // SceneError if released
}

/// Warns (RuntimeWarning) when the steps it watched changed the scene's point layout (a scheduled
/// refinement): NumPy views of positions and velocities taken before point at freed memory.
/// Declared before the GIL is released, so that it warns with the GIL held again.
class LayoutWatch {
 public:
  explicit LayoutWatch(const PythonScene& owner) : owner_(owner), revision_(owner.scene().layoutRevision()) {}
  ~LayoutWatch() {
    if (owner_.scene().layoutRevision() == revision_) return;
    // A warning turned into an error by the warnings filter cannot propagate from a destructor:
    // it is printed as unraisable instead.
    if (PyErr_WarnEx(PyExc_RuntimeWarning,
                     "the scene's point layout changed during these steps (a scheduled refinement): views of "
                     "positions and velocities taken before are stale, take them again",
                     1) != 0)
      PyErr_WriteUnraisable(nullptr);
  }
  LayoutWatch(const LayoutWatch&) = delete;
  LayoutWatch& operator=(const LayoutWatch&) = delete;

 private:
  const PythonScene& owner_;
  long revision_;
};

py::dict timing(const PythonScene& owner) {
  const StepTiming& t = owner.timing();
  const double simulated = t.steps * owner.scene().settings().dt;
  py::dict out;
  out["steps"] = t.steps;
  out["wall_s"] = t.total;
  out["mean_step_s"] = t.steps ? t.total / t.steps : 0.0;
  out["max_step_s"] = t.max;
  out["last_step_s"] = t.last;
  // > 1: faster than real time.
  out["real_time_factor"] = t.total > 0.0 ? simulated / t.total : 0.0;
  return out;
}

}  // namespace

void bindScene(py::module_& m) {
  py::class_<PythonScene, std::shared_ptr<PythonScene>>(
      m, "Scene",
      "A loaded and checked scene (filum.load or filum.load_dict). step() and run() advance it;\n"
      "a failed step raises filum.StepError with the scene rolled back to the state before it.\n"
      "q and v are read-only views of the whole state (no copy); state() is a copy.")
      .def_property_readonly("name", [](const PythonScene& s) { return s.scene().settings().name; })
      .def_property_readonly("source", [](const PythonScene& s) { return s.scene().settings().source; })
      .def_property_readonly("dt", [](const PythonScene& s) { return s.scene().settings().dt; }, "time step (s)")
      .def_property_readonly("duration", [](const PythonScene& s) { return s.scene().settings().duration; },
                             "the scene's run length (s)")
      .def_property_readonly("gravity", [](const PythonScene& s) { return Vec3(s.scene().settings().gravity); },
                             "(m/s²)")
      .def_property_readonly("time", [](const PythonScene& s) { return s.scene().state().time; }, "(s)")
      .def_property_readonly("step_count", [](const PythonScene& s) { return s.scene().stepCount(); })
      .def_property_readonly("layout_revision", [](const PythonScene& s) { return s.scene().layoutRevision(); },
                             "counts changes of the point layout (refinements): views taken before are stale")
      .def(
          "step",
          [](PythonScene& s) {
            const LayoutWatch watch(s);
            py::gil_scoped_release release;
            s.step();
          },
          "one time step of dt")
      .def(
          "run",
          [](PythonScene& s, std::optional<double> duration) {
            const double d = duration.value_or(s.scene().settings().duration);
            const LayoutWatch watch(s);
            py::gil_scoped_release release;
            return s.run(d);
          },
          py::arg("duration") = py::none(),
          "steps for `duration` seconds (default: the scene's duration), rounded to whole steps;\n"
          "returns the number of steps")
      .def_property_readonly("bodies", [](const std::shared_ptr<PythonScene>& s) { return bodyList(s); })
      .def("body", &bodyNamed, py::arg("path"), "the body held by the node at `path` (KeyError if none)")
      .def_property_readonly("q", [](const std::shared_ptr<PythonScene>& s) { return vectorView(s, s->scene().state().q); },
                             "all positions, read-only view (no copy)")
      .def_property_readonly("v", [](const std::shared_ptr<PythonScene>& s) { return vectorView(s, s->scene().state().v); },
                             "all velocities, read-only view (no copy)")
      .def("state", [](const PythonScene& s) { return SceneState(s.scene().state()); }, "a copy of the state")
      .def("set_state", [](PythonScene& s, const SceneState& state) { s.scene().setState(state); }, py::arg("state"),
           "restores a state taken by state() (SceneError if the layout changed since)")
      .def(
          "energy",
          [](const PythonScene& s) {
            const Energy e = s.scene().energy(s.scene().state());
            py::dict out;
            out["kinetic"] = e.kinetic;
            out["potential"] = e.potential;
            out["total"] = e.total();
            return out;
          },
          "kinetic and potential (gravity + elastic) energy (J)")
      // velocity: None for at rest (an Eigen default would import numpy when the module loads).
      .def(
          "steer",
          [](PythonScene& s, const std::string& name, const Vec3& position, std::optional<Vec3> velocity) {
            steer(s, name, position, velocity.value_or(Vec3::Zero()));
          },
          py::arg("constraint"), py::arg("position"), py::arg("velocity") = py::none(),
           "moves the target of a point constraint (a grip, a needle hole: its \"name\") between steps:\n"
           "from now on X(t) = position + velocity (t - now), m and m/s, until steered again. The\n"
           "constraint pulls its point there (Baumgarte stabilization); not part of state(). A constraint\n"
           "that has let its point go (\"release_at\", a cut) is refused (SceneError)")
      .def(
          "target",
          [](const PythonScene& s, const std::string& name) {
            return Vec3(targetConstraint(s, name).target().position(s.scene().state()));
          },
          py::arg("constraint"), "where the point constraint holds its point now (m)")
      .def("contacts", [](const PythonScene& s) { return contacts(s); },
           "contacts of the last step as arrays (copies): body, abscissa, point (k×3, m), force on the\n"
           "body (k×3, N), obstacle (−1: between threads), other_body (−1: obstacle),\n"
           "inside_lumen (1: the body is held inside other_body's lumen, a wire in a catheter)")
      .def("render", &renderFrame,
           "the scene drawn from its camera (or one framing it) as an H×W×3 uint8 RGB array;\n"
           "raises filum.RenderingError when this build or machine cannot render")
      .def_property_readonly("timing", &timing,
                             "wall time of the steps taken through this object: steps, wall_s, mean_step_s,\n"
                             "max_step_s, last_step_s, real_time_factor (simulated / wall)")
      .def("__repr__", [](const PythonScene& s) {
        return "<filum.Scene '" + s.scene().settings().name + "' t=" + std::to_string(s.scene().state().time) + " s>";
      });

  m.def(
      "load",
      [](const py::object& path) {
        // str or any path-like object (pathlib.Path).
        const std::string file = py::str(py::module_::import("os").attr("fspath")(path));
        return std::make_shared<PythonScene>(readJsonFile(file), file);
      },
      py::arg("path"), "loads and checks a scene file; filum.SceneError names the file and JSON path of a fault");
  m.def(
      "load_dict",
      [](const py::handle& document, const std::string& source) {
        return std::make_shared<PythonScene>(jsonFromPython(document, source), source);
      },
      py::arg("document"), py::arg("source") = "<dict>",
      "loads and checks a scene given as a dict (the scene file's JSON); `source` names it in errors");
}

}  // namespace filum::python
