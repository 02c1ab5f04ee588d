// ClampConstraint: the point of abscissa s of a spline is held at a target AND its tangent is
// held along a direction d — a cantilever's built-in end, or an instrument (needle holder,
// forceps) gripping a thread or a tube. 5 rows:
//   position   g_p = P(s, t) − X(t)          (3 rows, m; X fixed, scripted or attached,
//                                             point_target.hpp),
//   direction  g_d = [u w]ᵀ P'(s, t)         (2 rows, m per unit abscissa; (d, u, w)
//                                             orthonormal, P'(s) = Σ_j b'_j(s) q_j),
// so P'(s) stays parallel to d while its length (the local stretch) stays free. The angle
// between P'(s) and d is |g_d| / |P'(s)|. The direction is fixed in space (default: the
// initial tangent); g_d also vanishes for P' antiparallel to d, an unstable configuration the
// stabilization never approaches from the initial one. Jacobians: ∂g_p/∂q_j = b_j(s) I,
// ∂g_d/∂q_j = b'_j(s) [u w]ᵀ: two anchors (b and b'). Baumgarte terms as for a fixed point:
//   rows: Σ_j b_j A_j − Ẍ = −2ω ġ_p − ω² g_p   (known Ẍ of a scripted target on the right),   [u w]ᵀ Σ_j b'_j A_j = −2ω ġ_d − ω² g_d.
#pragma once

#include <memory>
#include <optional>

#include "filum/constraints/baumgarte.hpp"
#include "filum/constraints/point_target.hpp"
#include "filum/core/body_point.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/params.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::constraints {

class ClampConstraint final : public Constraint, public TargetConstraint {
 public:
  /// direction: non-zero (normalized), nullopt: the initial tangent P'(s).
  ClampConstraint(double abscissa, PointTarget target, std::optional<Vec3> direction,
                  Baumgarte stabilization = Baumgarte());

  /// "abscissa": s, "target"/"path" (default: initial P(s)), "direction": [x,y,z] (non-zero,
  /// default: initial tangent), "stabilization": ω (1/s).
  static std::unique_ptr<ClampConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "ClampConstraint"; }
  int rowCount() const override { return 5; }
  void buildRows(const SceneState& s, ConstraintRows& rows) const override;
  /// 3 position entries (m), then the 2 direction entries (m per unit abscissa).
  void violation(const SceneState& s, VecX& g, int first) const override;

  double abscissa() const { return abscissa_; }
  void actingAbscissas(const SceneState&, std::vector<double>& out) const override {
    if (active()) out.push_back(abscissa_);
  }
  const Vec3& direction() const { return direction_; }
  const PointTarget& target() const override { return target_; }
  PointTarget& target() override { return target_; }

 private:
  void init(const Scene& scene) override;

  double abscissa_;
  PointTarget target_;
  std::optional<Vec3> requested_direction_;
  Baumgarte baumgarte_;
  Vec3 direction_ = Vec3::UnitX();  // d
  Vec3 u_ = Vec3::UnitY(), w_ = Vec3::UnitZ();  // ⊥ d
  BodyPoint point_;  // the clamped point (body, s, its row)
};

}  // namespace filum::constraints
