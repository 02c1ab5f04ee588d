#include "filum/geometry/spline_basis_factory.hpp"

#include <stdexcept>

#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::geometry {

const std::vector<std::string>& splineBasisNames() {
  static const std::vector<std::string> names{"uniform_cubic_bspline", "catmull_rom", "nubs"};
  return names;
}

std::unique_ptr<CurveBasis> makeSplineBasis(const SplineBasisSpec& spec) {
  if (spec.name == "uniform_cubic_bspline") return std::make_unique<UniformCubicBSpline>(spec.control_points);
  if (spec.name == "catmull_rom") return std::make_unique<CatmullRomSpline>(spec.control_points);
  if (spec.name == "nubs") {
    if (!spec.knots.empty()) {
      auto basis = std::make_unique<NonUniformBSpline>(spec.degree, spec.knots);
      if (basis->controlPointCount() != spec.control_points)
        throw std::invalid_argument("nubs: " + std::to_string(spec.knots.size()) + " knots of degree " +
                                    std::to_string(spec.degree) + " define " +
                                    std::to_string(basis->controlPointCount()) + " control points, but " +
                                    std::to_string(spec.control_points) + " were given (knots = n + degree + 1)");
      return basis;
    }
    if (spec.degree < kMinimumSplineDegree || spec.degree > kMaximumSplineDegree)
      throw std::invalid_argument("nubs: degree must be in [1, 5], got " + std::to_string(spec.degree));
    if (spec.control_points < spec.degree + 1)
      throw std::invalid_argument("nubs: a degree " + std::to_string(spec.degree) + " B-spline needs at least " +
                                  std::to_string(spec.degree + 1) + " control points, got " +
                                  std::to_string(spec.control_points));
    return std::make_unique<NonUniformBSpline>(spec.degree, spec.clamped
                                                                ? clampedUniformKnots(spec.degree, spec.control_points)
                                                                : uniformKnots(spec.degree, spec.control_points));
  }
  std::string known;
  for (const std::string& name : splineBasisNames()) known += (known.empty() ? "" : ", ") + name;
  throw std::invalid_argument("unknown spline basis '" + spec.name + "' (known: " + known + ")");
}

}  // namespace filum::geometry
