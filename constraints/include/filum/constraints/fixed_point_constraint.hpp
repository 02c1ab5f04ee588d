// FixedPointConstraint: the point of abscissa s of a spline is held at a target,
// g(q, t) = P(s, t) − X(t) = Σ_j b_j(s) q_j − X(t) = 0 (3 rows, paper §4 and Fig. 1a).
// Rows of L A = E with Baumgarte stabilization (critically damped, ω in 1/s):
//   Σ_j b_j(s) A_j = Ẍ(t) − 2ω (Σ_j b_j(s) q̇_j − Ẋ(t)) − ω² g.
#pragma once

#include <memory>
#include <optional>

#include "filum/constraints/scripted_path.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/params.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::constraints {

class FixedPointConstraint final : public Constraint {
 public:
  /// abscissa in [0, 1]; target: fixed position (nullopt: where P(s) starts); path: scripted
  /// motion (overrides target when not empty); stabilization ω (1/s) >= 0, 0 disables it
  /// (acceleration-level constraint only, which drifts), nullopt: one tenth of 1/dt.
  FixedPointConstraint(double abscissa, std::optional<Vec3> target, ScriptedPath path,
                       std::optional<double> stabilization);

  /// "abscissa": s, "target": [x,y,z] (default: initial P(s)), "path": keyframes,
  /// "stabilization": ω (1/s, default 0.1/dt).
  static std::unique_ptr<FixedPointConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "FixedPointConstraint"; }
  int rowCount() const override { return 3; }
  void buildRows(const SceneState& s, ConstraintRows& rows) const override;
  void violation(const SceneState& s, VecX& g, int first) const override;

  double abscissa() const { return abscissa_; }
  double stabilization() const { return omega_.value_or(0.0); }
  /// X(t)
  Vec3 targetAt(double t) const { return path_.empty() ? *target_ : path_.position(t); }

 private:
  void init(const Scene& scene) override;

  double abscissa_;
  std::optional<Vec3> target_;
  ScriptedPath path_;
  std::optional<double> omega_;
  geometry::BasisRow row_;  // basis at the abscissa (constant)
};

}  // namespace filum::constraints
