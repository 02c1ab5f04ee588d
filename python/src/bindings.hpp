// The pieces of the Python module `filum` (module.cpp puts them together), one file each:
// the state and its NumPy views (bind_state.cpp), the bodies (bind_body.cpp), the scene
// (bind_scene.cpp).
#pragma once

#include <memory>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "filum/core/types.hpp"
#include "python_scene.hpp"

namespace filum::python {

namespace py = pybind11;

/// A read-only n × 3 NumPy view (no copy) of points [offset, offset + count) of a global vector
/// of the scene's state (q or v), kept alive by the scene's Python object.
py::array pointsView(const std::shared_ptr<PythonScene>& owner, const VecX& global, int offset, int count);
/// A read-only 1-D view of the whole vector.
py::array vectorView(const std::shared_ptr<PythonScene>& owner, const VecX& global);
/// Copies an array-like of shape (rows, 3) into Points; ValueError naming `what` otherwise.
Points pointsFromArray(const py::handle& array, int rows, const std::string& what);

/// Every body of the scene as filum.Body objects; the one at a node path (KeyError listing them).
py::list bodyList(const std::shared_ptr<PythonScene>& owner);
py::object bodyNamed(const std::shared_ptr<PythonScene>& owner, const std::string& path);

void bindState(py::module_& m);
void bindBody(py::module_& m);
void bindScene(py::module_& m);

}  // namespace filum::python
