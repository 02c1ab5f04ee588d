#include "filum/geometry/mesh_units.hpp"

namespace filum::geometry {

double meshScale(const Params& p) {
  const std::string units = p.string("units", "m");
  const double metres_per_unit = units == "m" ? 1.0 : units == "cm" ? 0.01 : units == "mm" ? 0.001 : 0.0;
  if (metres_per_unit == 0.0) p.fail("units", "\"m\", \"cm\" or \"mm\" (the unit of the file's coordinates)");
  return metres_per_unit * p.positive({"scale", "1"}, 1.0);
}

}  // namespace filum::geometry
