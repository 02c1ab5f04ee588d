// filum.State (a copy of the scene's SceneState: time, steps, q, v) and the NumPy views that
// read the live state without copying.
#include <string>

#include <pybind11/eigen.h>

#include "bindings.hpp"
#include "filum/core/scene_state.hpp"

namespace filum::python {

namespace {

/// The view's data stay the scene's: NumPy may not write into them (writes go through
/// set_positions / set_velocities / set_state, which check the shape and the layout).
py::array readOnly(py::array a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

}  // namespace

py::array pointsView(const std::shared_ptr<PythonScene>& owner, const VecX& global, int offset, int count) {
  const auto stride = static_cast<py::ssize_t>(sizeof(double));
  return readOnly(py::array_t<double>({static_cast<py::ssize_t>(count), py::ssize_t{3}}, {3 * stride, stride},
                                      global.data() + 3 * static_cast<std::ptrdiff_t>(offset), py::cast(owner)));
}

py::array vectorView(const std::shared_ptr<PythonScene>& owner, const VecX& global) {
  return readOnly(py::array_t<double>({static_cast<py::ssize_t>(global.size())}, {py::ssize_t{sizeof(double)}},
                                      global.data(), py::cast(owner)));
}

Points pointsFromArray(const py::handle& array, int rows, const std::string& what) {
  const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  if (!a || a.ndim() != 2 || a.shape(0) != rows || a.shape(1) != 3) {
    std::string found = "an object that is not a numeric array";
    if (a) {
      found = "shape (";
      for (py::ssize_t i = 0; i < a.ndim(); ++i) found += (i ? ", " : "") + std::to_string(a.shape(i));
      found += a.ndim() == 1 ? ",)" : ")";
    }
    throw py::value_error(what + ": expected an array of shape (" + std::to_string(rows) + ", 3), found " + found);
  }
  Points out(rows, 3);
  std::copy(a.data(), a.data() + 3 * rows, out.data());
  if (!out.allFinite()) throw py::value_error(what + ": expected finite values, found NaN or infinity");
  return out;
}

void bindState(py::module_& m) {
  py::class_<SceneState>(m, "State",
                         "A copy of the whole simulation state (Scene.state()); Scene.set_state() puts it back.\n"
                         "q, v: positions and velocities, 3 coordinates per control point of every body in order,\n"
                         "then the constraints' extra DOFs (a sliding point's abscissa).")
      .def_readonly("time", &SceneState::time, "simulated time (s)")
      .def_readonly("steps", &SceneState::steps, "steps taken since t = 0")
      .def_property_readonly("q", [](const SceneState& s) { return VecX(s.q); }, "positions (m), a copy")
      .def_property_readonly("v", [](const SceneState& s) { return VecX(s.v); }, "velocities (m/s), a copy")
      .def("__repr__", [](const SceneState& s) {
        return "<filum.State t=" + std::to_string(s.time) + " s, " + std::to_string(s.q.size()) + " coordinates>";
      });
}

}  // namespace filum::python
