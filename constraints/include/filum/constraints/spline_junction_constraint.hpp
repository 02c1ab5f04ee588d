// SplineJunctionConstraint: joins two splines ([Lenoir talk 2008], fallopian tubes: "3 dynamic splines
// connected to keep the continuity ... 9 constraints per junction", released to cut). The
// point of abscissa s1 of this body (default 1, its end) and the point of abscissa s2 of the
// other body (default 0, its start) are joined with parametric continuity C^k, k ∈ {0, 1, 2}:
//   g_0 = P1(s1) − P2(s2)              (position,  3 rows, m)
//   g_1 = P1'(s1) − ρ P2'(s2)          (tangent,   3 rows, m per unit abscissa)      k >= 1
//   g_2 = P1''(s1) − ρ² P2''(s2)       (curvature, 3 rows, m per unit abscissa²)    k >= 2
// ρ = ℓ1/ℓ2 relates the two parameters to one running along both curves, u = ℓ1 s1 on the
// first and u = ℓ1 + ℓ2 s2 on the second: dP1/du = P1'/ℓ1 must equal dP2/du = P2'/ℓ2, and
// d²P/du² likewise with ℓ². By default ρ = |P1'(s1)| / |P2'(s2)| at t = 0 (ℓ1/ℓ2 for
// straight, evenly spaced threads), so that a C1-continuous initial shape satisfies g_1 = 0.
// Every row is linear in q: ∂g_k/∂q = [b1^(k)(s1) on body 1, −ρ^k b2^(k)(s2) on body 2] ⊗ I —
// one anchor per order spanning both bodies, three directions each. Baumgarte terms as for a
// fixed point: rows Σ b1^(k) A1 − ρ^k Σ b2^(k) A2 = −2ω ġ_k − ω² g_k.
// A body may be joined to itself (s1 ≠ s2): a closed loop.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "filum/constraints/baumgarte.hpp"
#include "filum/core/body_point.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/params.hpp"
#include "filum/geometry/spline_basis.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::constraints {

class SplineJunctionConstraint final : public Constraint {
 public:
  /// other: node path of the second spline; continuity ∈ {0, 1, 2}; ratio ρ > 0 (nullopt:
  /// from the initial tangents).
  SplineJunctionConstraint(std::string other, double abscissa, double other_abscissa, int continuity,
                           std::optional<double> ratio, Baumgarte stabilization = Baumgarte());

  /// "other": node path (required), "abscissa": s1 (default 1), "other_abscissa": s2
  /// (default 0), "continuity": 0, 1 or 2 (default 2), "ratio": ρ > 0 (default from the
  /// initial tangents), "stabilization": ω (1/s).
  static std::unique_ptr<SplineJunctionConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "SplineJunctionConstraint"; }
  int rowCount() const override { return 3 * (continuity_ + 1); }
  void buildRows(const SceneState& s, ConstraintRows& rows) const override;
  /// g_0, then g_1 and g_2 as present (3 entries each).
  void violation(const SceneState& s, VecX& g, int first) const override;

  int continuity() const { return continuity_; }
  double ratio() const { return ratio_; }
  const CurveBody& other() const { return *other_; }
  double abscissa() const { return abscissa_; }
  double otherAbscissa() const { return other_abscissa_; }

 private:
  void init(const Scene& scene) override;
  /// g_k and ġ_k at state s.
  void jump(const SceneState& s, int order, Vec3& g, Vec3& dg) const;

  std::string other_path_;
  std::string other_where_;  // JSON place of "other", for messages
  double abscissa_, other_abscissa_;
  int continuity_;
  std::optional<double> requested_ratio_;
  Baumgarte baumgarte_;
  double ratio_ = 1.0;
  const CurveBody* other_ = nullptr;
  BodyPoint own_point_, other_point_;  // the joined points (s1 on this body, s2 on the other)
};

}  // namespace filum::constraints
