// Python objects (a scene given as a dict) to nlohmann::json, value by value: floats stay
// doubles (NaN and infinities included, so that the scene loader refuses them naming their JSON
// path, as it does in a file), and a value JSON cannot hold is refused naming its path.
#pragma once

#include <string>

#include <nlohmann/json.hpp>
#include <pybind11/pybind11.h>

namespace filum::python {

/// Throws pybind11::type_error "<source>: <JSON pointer>: ..." for a value of another type than
/// dict (str keys), list, tuple, str, bool, int, float, None or a NumPy scalar or array.
nlohmann::json jsonFromPython(pybind11::handle value, const std::string& source, const std::string& path = "");

}  // namespace filum::python
