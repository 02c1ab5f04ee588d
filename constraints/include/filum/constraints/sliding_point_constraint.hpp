// SlidingPointConstraint: the suture constraint of [Lenoir talk 2008] — a thread passes through a point
// P0 (a needle hole in tissue) and may slide through it:
//   g(q, s, t) = P(s(t), t) − X(t) = 0,
// where the abscissa s(t) of the curve point in the hole is a free unknown (an extra DOF of
// the scene state, scene_state.hpp) and X(t) = P0 is fixed, scripted or a point of another
// spline (point_target.hpp). The Lagrange formalism gives s its own equation: s carries no
// mass, so the constraint force cannot work along it,
//   (∂g/∂s)ᵀ λ = P'(s)ᵀ λ = 0         — λ is normal to the thread (frictionless sliding).
// Second derivative, with t = P'(s), Ṗ' = Σ_j b'_j(s) q̇_j, ġ = Ṗ(s) + t ṡ − Ẋ:
//   g̈ = Σ_j b_j(s) A_j − Ẍ + t s̈ + 2 Ṗ' ṡ + P''(s) ṡ²,
// and the Baumgarte law g̈ = −2ω ġ − ω² g splits along the normal plane N = [n1 n2] ⊥ t and
// along t (the multiplier only has normal components, λ = N μ):
//   rows (2):        Nᵀ (Σ_j b_j A_j − Ẍ) = Nᵀ r,    r = −2 Ṗ' ṡ − P'' ṡ² − 2ω ġ − ω² g,
//   direct relation: s̈ = tᵀ (r − (Σ_j b_j A_j − Ẍ)) / |t|²   ([Lenoir talk 2008]: "resolution
//                    acceleration by giving a direct relation to compute s").
// (a known Ẍ — a scripted hole — is moved into r; an attached hole's Ẍ = Σ b2 A2 stays in L).
// So the sliding point costs 2 rows in the multiplier system and one scalar after it.
//
// Why s is integrated with the points (instead of re-projected after each step): s̈ above is
// exact, so RK4 advances (q, s) together with its fourth order and the hole stays on the
// thread to the integrator's O(dt⁵) local error, pulled back by the Baumgarte terms along
// every direction (the tangential ones through s̈). A position-level re-projection would leave
// a normal gap ½ κ |Δs P'|² per step where the thread curves (κ its curvature).
//
// Optional viscous friction along the tangent (N·s/m): the thread's material velocity
// relative to the hole, u = Ṗ(s) − Ẋ (= −t ṡ while g = 0), is opposed by
//   F = −η t̂ (t̂ · u),   t̂ = t / |t|,
// a known force applied at P(s) (B_j += b_j(s) F) and, for an attached hole, −F on the other
// body. It is explicit: stable while η dt / m_eff < 2 for the sliding mass m_eff it drags.
//
// The thread slides out of the hole when s leaves [0, 1]: the constraint is then released. So it
// is at a cut of the thread (CurveBasis::cuts): a cut strand's end slides out of the hole as the
// thread's own ends do, rather than the hole passing on to the other strand. Releases are a
// function of the state: at a step's start the point is released when it is at a cut or moving
// towards one that it reaches within twice its step, |c − s| <= 2 |ṡ| dt (twice: ṡ changes over the
// step; a point released a step early has only its last sliding step left); from then on, as a
// scheduled release is (a state restored from before that time holds the thread again).
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "filum/constraints/baumgarte.hpp"
#include "filum/core/body_point.hpp"
#include "filum/constraints/point_target.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/params.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::constraints {

class SlidingPointConstraint final : public Constraint, public TargetConstraint {
 public:
  /// abscissa: initial s(0) ∈ [0, 1]; friction η (N·s/m) >= 0.
  SlidingPointConstraint(double abscissa, PointTarget target, double friction,
                         Baumgarte stabilization = Baumgarte());

  /// "abscissa": initial s, "target"/"path": the hole (default: initial P(s)),
  /// "friction": η (N·s/m, default 0), "stabilization": ω (1/s).
  static std::unique_ptr<SlidingPointConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "SlidingPointConstraint"; }
  int rowCount() const override { return 2; }
  void buildRows(const SceneState& s, ConstraintRows& rows) const override;
  /// The whole gap P(s) − X (3 entries, m), not only its normal part.
  int violationCount() const override { return 3; }
  void violation(const SceneState& s, VecX& g, int first) const override;
  void addForce(const SceneState& s, VecX& B) const override;

  int extraDofCount() const override { return 1; }
  void initialExtra(VecX& q) const override { q[extraIndex()] = initial_abscissa_; }
  void extraAcceleration(const SceneState& s, VecX& a) const override;
  bool releasedAt(const SceneState& s) const override;

  /// s(t) and ṡ(t) at state s.
  double abscissa(const SceneState& s) const { return s.q[extraIndex()]; }
  double abscissaRate(const SceneState& s) const { return s.v[extraIndex()]; }
  /// Where the thread is in the hole now.
  void actingAbscissas(const SceneState& s, std::vector<double>& out) const override {
    if (active()) out.push_back(abscissa(s));
  }
  double friction() const { return friction_; }
  const PointTarget& target() const override { return target_; }
  PointTarget& target() override { return target_; }
  std::optional<Vec3> targetPoint(const SceneState& s) const override { return target_.position(s); }
  bool hasTargetPoint() const override { return true; }
  /// P(s(t)) − X(t).
  Vec3 gap(const SceneState& s) const;
  /// Forgets a release by a cut end reaching the hole (a point held again elsewhere: a wound's hole
  /// engaging a parked sliding point, haptics/wound.hpp).
  void rearm() { cut_release_time_.reset(); }

 private:
  void init(const Scene& scene) override;
  /// Curve quantities at the current s of state st.
  struct Local {
    BodyPoint point;  // the point at the current s
    Vec3 p, t, pss;   // P(s), P'(s), P''(s)
    Vec3 pdot, tdot;  // Ṗ(s) = Σ b_j q̇_j, Ṗ'(s) = Σ b'_j q̇_j
    Vec3 r;           // Ẍ_known − 2 Ṗ' ṡ − P'' ṡ² − 2ω ġ − ω² g
  };
  Local evaluate(const SceneState& st) const;

  double initial_abscissa_;
  std::vector<double> cuts_;  // of the thread, as of the last binding (a cut rebinds)
  double dt_ = 0.0;
  mutable std::optional<double> cut_release_time_;  // the time a cut end reached the hole
  PointTarget target_;
  double friction_;
  Baumgarte baumgarte_;
  const CurveBody* spline_ = nullptr;
};

}  // namespace filum::constraints
