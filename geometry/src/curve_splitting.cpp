#include "filum/geometry/curve_splitting.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

#include "filum/geometry/knot_insertion.hpp"
#include "filum/geometry/knot_vector.hpp"

namespace filum::geometry {

SplitCurve splitCurve(const BSplineCurve& curve, double s) {
  validateBSplineCurve(curve, "splitCurve");
  if (!(s > 0.0 && s < 1.0))
    throw std::invalid_argument("splitCurve: the split abscissa must be in (0, 1), got " + std::to_string(s));
  const int d = curve.degree, n = curve.controlPointCount();
  const double start = curve.knots[d], end = curve.knots[n], width = end - start;
  double u = start + s * width;
  // Snap onto an existing knot closer than 8 ulps of the domain width.
  const double snap = 8.0 * std::numeric_limits<double>::epsilon() * std::max(std::abs(start), std::abs(end));
  for (double knot : curve.knots)
    if (std::abs(knot - u) <= snap) u = knot;
  return splitCurveAtParameter(curve, u);
}

SplitCurve splitCurveAtParameter(const BSplineCurve& curve, double u) {
  validateBSplineCurve(curve, "splitCurveAtParameter");
  const int d = curve.degree, n = curve.controlPointCount();
  const double start = curve.knots[d], end = curve.knots[n];
  if (!(u > start && u < end)) {
    std::ostringstream m;
    m.precision(17);
    m << "splitCurveAtParameter: u = " << u << " is not strictly inside the domain (" << start << ", " << end << ")";
    throw std::invalid_argument(m.str());
  }
  // Raise the multiplicity of u to d + 1 (exact).
  const int missing = d + 1 - knotMultiplicity(curve.knots, u);
  const BSplineCurve full = missing > 0 ? insertKnots(curve, std::vector<double>(missing, u)) : curve;
  const int a = static_cast<int>(std::lower_bound(full.knots.begin(), full.knots.end(), u) - full.knots.begin());
  const int total = full.controlPointCount();

  SplitCurve out;
  out.split_abscissa = (u - start) / (end - start);
  out.before.degree = out.after.degree = d;
  out.before.knots.assign(full.knots.begin(), full.knots.begin() + a + d + 1);
  out.before.control_points = full.control_points.topRows(a);
  out.after.knots.assign(full.knots.begin() + a, full.knots.end());
  out.after.control_points = full.control_points.bottomRows(total - a);
  out.refinement = knotInsertionMatrix(d, curve.knots, full.knots);
  validateBSplineCurve(out.before, "splitCurve (first piece)");
  validateBSplineCurve(out.after, "splitCurve (second piece)");
  return out;
}

}  // namespace filum::geometry
