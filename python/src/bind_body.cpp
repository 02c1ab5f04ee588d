// filum.Body: one body of a scene (a dynamic spline): its control points and velocities as NumPy
// views into the scene's state, writes that go through the scene, and its curve P(s).
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/stl.h>

#include "bindings.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::python {

namespace {

/// A body by its index in Scene::bodies(), holding its scene alive. Bodies are never removed,
/// so the index stays valid; the point count is read anew at every call (refinement changes it).
struct PythonBody {
  std::shared_ptr<PythonScene> owner;
  int index;

  MechanicalState& state() const { return *owner->scene().bodies()[index]; }
  std::string name() const { return state().node() ? state().node()->path() : state().name(); }
  const CurveBody& curve() const {
    const CurveBody* c = state().curve();
    if (!c) throw py::type_error("body '" + name() + "' is not a curve (no P(s))");
    return *c;
  }
  /// Writes `points` into this body's block of q or v through Scene::setState.
  void write(const py::handle& array, bool velocities) const {
    SceneState s = owner->scene().state();
    const std::string what = "body '" + name() + "' " + (velocities ? "velocities" : "positions");
    const Points p = pointsFromArray(array, state().pointCount(), what);
    state().block(velocities ? s.v : s.q) = p;
    owner->scene().setState(s);
  }
  /// P(s) (or Ṗ(s) from the velocities) at every abscissa of `abscissas`, m × 3.
  Points sample(const std::vector<double>& abscissas, bool velocities) const {
    const CurveBody& c = curve();
    const VecX& x = velocities ? owner->scene().state().v : owner->scene().state().q;
    Points out(static_cast<int>(abscissas.size()), 3);
    for (std::size_t i = 0; i < abscissas.size(); ++i) {
      const double s = abscissas[i];
      if (!(s >= 0.0 && s <= 1.0))
        throw py::value_error("body '" + name() + "': abscissa " + std::to_string(i) + " is " + std::to_string(s) +
                              ", expected s in [0, 1]");
      out.row(static_cast<int>(i)) = c.position(x, s).transpose();
    }
    return out;
  }
};

}  // namespace

py::list bodyList(const std::shared_ptr<PythonScene>& owner) {
  py::list out;
  for (int i = 0; i < static_cast<int>(owner->scene().bodies().size()); ++i) out.append(PythonBody{owner, i});
  return out;
}

py::object bodyNamed(const std::shared_ptr<PythonScene>& owner, const std::string& path) {
  const auto& bodies = owner->scene().bodies();
  std::string known;
  for (int i = 0; i < static_cast<int>(bodies.size()); ++i) {
    const PythonBody body{owner, i};
    if (body.name() == path) return py::cast(body);
    known += (known.empty() ? "'" : ", '") + body.name() + "'";
  }
  throw py::key_error("no body at node '" + path + "'; the bodies are " + (known.empty() ? "none" : known));
}

void bindBody(py::module_& m) {
  py::class_<PythonBody>(m, "Body",
                         "A body of the scene. positions and velocities are read-only NumPy views into the\n"
                         "scene's state (no copy): they follow the simulation step after step, and stay valid\n"
                         "while the body's point count does not change (Scene.layout_revision counts the\n"
                         "changes; a scheduled refinement makes old views stale: take them again).\n"
                         "set_positions / set_velocities copy an (n, 3) array into the state. sample(s) and\n"
                         "sample_velocity(s) compute new arrays.")
      .def_property_readonly("name", &PythonBody::name, "the node path of the body")
      .def_property_readonly("point_count", [](const PythonBody& b) { return b.state().pointCount(); })
      .def_property_readonly("offset", [](const PythonBody& b) { return b.state().offset(); },
                             "index of its first point in the scene's state (q[3*offset:])")
      .def_property_readonly("mass", [](const PythonBody& b) { return b.curve().mass(); }, "total mass (kg)")
      .def_property_readonly("radius", [](const PythonBody& b) { return b.curve().radius(); }, "radius (m)")
      .def_property_readonly(
          "positions",
          [](const PythonBody& b) {
            return pointsView(b.owner, b.owner->scene().state().q, b.state().offset(), b.state().pointCount());
          },
          "control points (m), n × 3, a read-only view of the state (no copy)")
      .def_property_readonly(
          "velocities",
          [](const PythonBody& b) {
            return pointsView(b.owner, b.owner->scene().state().v, b.state().offset(), b.state().pointCount());
          },
          "control point velocities (m/s), n × 3, a read-only view of the state (no copy)")
      .def("set_positions", [](const PythonBody& b, const py::handle& a) { b.write(a, false); }, py::arg("points"),
           "copies an (n, 3) array of control points (m) into the state")
      .def("set_velocities", [](const PythonBody& b, const py::handle& a) { b.write(a, true); }, py::arg("velocities"),
           "copies an (n, 3) array of control point velocities (m/s) into the state")
      .def("sample", [](const PythonBody& b, const std::vector<double>& s) { return b.sample(s, false); },
           py::arg("abscissas"), "P(s) at each abscissa s in [0, 1] (m), a new m × 3 array")
      .def("sample_velocity", [](const PythonBody& b, const std::vector<double>& s) { return b.sample(s, true); },
           py::arg("abscissas"), "dP/dt(s) at each abscissa s in [0, 1] (m/s), a new m × 3 array")
      .def("__repr__", [](const PythonBody& b) {
        return "<filum.Body '" + b.name() + "', " + std::to_string(b.state().pointCount()) + " points>";
      });
}

}  // namespace filum::python
