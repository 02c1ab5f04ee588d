// FixedPointConstraint: the point of abscissa s of a spline is held at a target,
// g(q, t) = P(s, t) − X(t) = Σ_j b_j(s) q_j − X(t) = 0 (3 rows, paper §4 and Fig. 1a). The
// target is fixed, scripted (a probe, an instrument) or a point of another spline (see
// point_target.hpp). Rows of L A = E with Baumgarte stabilization (critically damped, ω in 1/s):
//   Σ_j b_j(s) A_j − Ẍ = −2ω (Σ_j b_j(s) q̇_j − Ẋ) − ω² g   (projected_point_constraint.hpp, D = I).
#pragma once

#include <memory>
#include <optional>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

class FixedPointConstraint final : public ProjectedPointConstraint {
 public:
  /// abscissa in [0, 1]; target (default: where P(s) starts); stabilization ω (1/s) >= 0,
  /// 0 disables it (acceleration-level constraint only, which drifts), default 0.1/dt.
  FixedPointConstraint(double abscissa, PointTarget target, Baumgarte stabilization = Baumgarte());
  /// Shorthand of the walking skeleton: fixed target (nullopt: initial P(s)) or scripted path.
  FixedPointConstraint(double abscissa, std::optional<Vec3> target, geometry::ScriptedPath path,
                       std::optional<double> stabilization);

  /// "abscissa": s, "target": [x,y,z] or {"object": node, "abscissa": s2} (default: initial
  /// P(s)), "path": keyframes, "stabilization": ω (1/s, default 0.1/dt).
  static std::unique_ptr<FixedPointConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "FixedPointConstraint"; }
};

}  // namespace filum::constraints
