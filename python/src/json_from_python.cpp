#include "json_from_python.hpp"

#include <pybind11/numpy.h>

namespace py = pybind11;

namespace filum::python {

nlohmann::json jsonFromPython(py::handle value, const std::string& source, const std::string& path) {
  const std::string where = source + ": " + (path.empty() ? "/" : path);
  if (value.is_none()) return nullptr;
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>();
  if (py::isinstance<py::int_>(value)) return value.cast<long long>();
  if (py::isinstance<py::float_>(value)) return value.cast<double>();
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::dict>(value)) {
    nlohmann::json object = nlohmann::json::object();
    for (const auto& [key, item] : value.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key))
        throw py::type_error(where + ": keys must be strings, found " + py::repr(key).cast<std::string>());
      const std::string name = key.cast<std::string>();
      object[name] = jsonFromPython(item, source, path + "/" + name);
    }
    return object;
  }
  // NumPy arrays (a control polygon) become nested lists, NumPy scalars numbers.
  if (py::isinstance<py::array>(value)) return jsonFromPython(value.attr("tolist")(), source, path);
  if (py::hasattr(value, "dtype") && py::hasattr(value, "item")) return jsonFromPython(value.attr("item")(), source, path);
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    nlohmann::json array = nlohmann::json::array();
    std::size_t i = 0;
    for (const auto& item : value) array.push_back(jsonFromPython(item, source, path + "/" + std::to_string(i++)));
    return array;
  }
  throw py::type_error(where + ": expected a JSON value (dict, list, str, number, bool, None), found " +
                       py::repr(value.get_type()).cast<std::string>());
}

}  // namespace filum::python
