// RadiusProfile: the radius of a generalized cylinder along its axis, r(u) with u ∈ [0, 1] the
// fraction of the rest arc length (so that a bulge stays on the same piece of tissue when the
// body stretches). Constant, or a monotone piecewise-cubic Hermite interpolant of (u_i, r_i)
// (F. N. Fritsch, R. E. Carlson, "Monotone piecewise cubic interpolation", SIAM J. Numer. Anal.
// 17(2), 1980): C1, so the skin's normals (which use dr/du) are continuous, and without
// overshoot, so r stays between neighbouring r_i and never goes below the smallest (> 0).
// Outside [u_0, u_last] the radius is constant.
#pragma once

#include <string>
#include <vector>

#include "filum/core/params.hpp"

namespace filum::visual {

class RadiusProfile {
 public:
  /// A constant radius r > 0 (m).
  explicit RadiusProfile(double radius = 1e-3);
  /// Knots u_i strictly increasing in [0, 1], radii r_i > 0 (m), same count >= 1. Throws
  /// std::invalid_argument naming the bad entry.
  RadiusProfile(std::vector<double> u, std::vector<double> r);

  /// "radius_profile": [[u, r], ...] if present, else "radius": r, else `fallback` (the body's
  /// radius). Errors name the file and JSON path.
  static RadiusProfile fromParams(const Params& p, double fallback);

  /// r(u) (m), u clamped to [0, 1].
  double radius(double u) const;
  /// dr/du (m per unit of u).
  double slope(double u) const;
  double maxRadius() const;
  bool constant() const { return u_.size() == 1; }

 private:
  int interval(double u) const;  // i with u_i <= u < u_{i+1}
  std::vector<double> u_, r_, m_;  // knots, radii, Hermite slopes dr/du
};

}  // namespace filum::visual
