// ProjectedPointConstraint: the point of abscissa s of a spline is held, along k fixed unit
// directions d_1..d_k, to a target X(t) (paper §4 and Fig. 1a):
//   g(q, t) = Dᵀ (P(s, t) − X(t)) = Dᵀ (Σ_j b_j(s) q_j − X(t)),   D = [d_1 .. d_k] (3 × k),
// k = 3 for a fixed point (D = I), 2 for a point on an axis (D ⊥ the axis), 1 for a point on a
// plane (D = the normal). Its Jacobian is ∂g/∂q_j = b_j(s) Dᵀ, so the k rows of L A = E share
// one anchor (b_j(s) on the body's points, −b_k(s2) on an attached target's) and differ only by
// their direction d_i (constraint_rows.hpp). With Baumgarte stabilization (baumgarte.hpp):
//   d_iᵀ (Σ_j b_j(s) A_j − Ẍ) = d_iᵀ (−2ω ġ − ω² g)_full,   ġ_full = Σ_j b_j(s) q̇_j − Ẋ,
// where Ẍ is known for fixed and scripted targets (moved to the right-hand side) and an
// unknown (in L) when attached.
#pragma once

#include <vector>

#include "filum/constraints/baumgarte.hpp"
#include "filum/constraints/point_target.hpp"
#include "filum/core/body_point.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/constraint.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::constraints {

class ProjectedPointConstraint : public Constraint, public TargetConstraint {
 public:
  int rowCount() const override { return static_cast<int>(directions_.size()); }
  void buildRows(const SceneState& s, ConstraintRows& rows) const override;
  void violation(const SceneState& s, VecX& g, int first) const override;

  double abscissa() const { return abscissa_; }
  /// Its point, while it holds (not released).
  void actingAbscissas(const SceneState&, std::vector<double>& out) const override {
    if (active()) out.push_back(abscissa_);
  }
  double stabilization() const { return baumgarte_.omega(); }
  const PointTarget& target() const override { return target_; }
  PointTarget& target() override { return target_; }
  std::optional<Vec3> targetPoint(const SceneState& s) const override { return target_.position(s); }
  bool hasTargetPoint() const override { return true; }
  /// The unit directions d_i of the rows.
  const std::vector<Vec3>& directions() const { return directions_; }
  /// X(t) of a fixed or scripted target.
  Vec3 targetAt(double t) const { return target_.positionAt(t); }
  /// P(s) − X(t) at state s (full 3D gap; the rows hold its projection Dᵀ).
  Vec3 gap(const SceneState& s) const;

 protected:
  /// abscissa in [0, 1]; directions: unit, mutually orthogonal.
  ProjectedPointConstraint(double abscissa, PointTarget target, Baumgarte baumgarte, std::vector<Vec3> directions);

 private:
  void init(const Scene& scene) override;

  double abscissa_;
  PointTarget target_;
  Baumgarte baumgarte_;
  std::vector<Vec3> directions_;
  BodyPoint point_;  // the constrained point (body, s, its row)
};

/// Two unit vectors that complete the unit vector a into an orthonormal basis (a, u, w).
std::pair<Vec3, Vec3> orthonormalComplement(const Vec3& a);

}  // namespace filum::constraints
