// TissueAttachment: the connective tissue that holds a hollow organ to the body wall — the
// mesosalpinx along a fallopian tube, the mesentery along the small bowel, a ligament — as a row
// of springs with dashpots from points of a curve body to fixed anchors.
//
// Points. `count` abscissas evenly over [from, to]: s_i = from + (i + ½)(to − from)/count, the
// midpoints of equal pieces, each standing for a piece of length ℓ = (to − from) L₀ / count of the
// curve (L₀ its length at the start).
// Anchors a_i: where the points lie at the start ("anchors": "initial", the default), or evenly
// along a root line ("root": {"from": [m], "to": [m]}) at the same fractions (the mesentery's root).
// Spring and dashpot of point i, d_i = P(s_i) − a_i, P(s) = Σ_j b_j(s) q_j:
//   E_i = ½ k_i (|d_i| − r_i)²  when |d_i| > r_i, 0 below (a sheet of tissue carries no compression),
//   k_i = k ℓ  (k, "stiffness": N/m per metre of curve, i.e. Pa — a Winkler foundation's modulus),
//   r_i = "rest_length" (m, default 0: the point is held where its anchor is), or "initial" (the
//         distance at the start: the sheet just taut);
//   Q_j = −b_j(s_i) [k_i (1 − r_i/|d_i|) d_i + c_i Ṗ(s_i)],   c_i = c ℓ ("damping", N·s/m per metre:
//         the tissue's viscosity, acting in every direction whether the sheet is taut or slack);
//   ∂Q_j/∂q_m = −b_j b_m k_i [(1 − r_i/|d_i|) I + (r_i/|d_i|) d̂ d̂ᵀ]   (taut; 0 slack),
//   ∂Q_j/∂q̇_m = −b_j b_m c_i I.
// With r_i = 0 and uniform k a straight curve under its weight q (N/m) sinks by q/k exactly,
// whatever its bending stiffness: a uniform load on a uniform foundation bends nothing.
//
// Abscissas keep their meaning through refinement and cuts (CurveBody::cut): a tube cut between
// two attachment points leaves each part held by its own springs, with the anchors and rest
// lengths of the start (computed once, at the first binding).
#pragma once

#include <memory>
#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/params.hpp"

namespace filum {
class CurveBody;
}

namespace filum::mechanics {

class TissueAttachment final : public ForceField {
 public:
  struct Settings {
    double from = 0.0, to = 1.0;  // abscissa span
    int count = 10;               // attachment points
    double stiffness = 0.0;       // k, N/m per metre of curve (Pa)
    double damping = 0.0;         // c, N·s/m per metre of curve
    bool root = false;            // anchors on the root line (else where the points start)
    Vec3 root_from = Vec3::Zero(), root_to = Vec3::Zero();
    bool initial_rest_length = false;  // r_i = the distance at the start
    double rest_length = 0.0;          // r (m) when not initial
  };
  static constexpr int kMaxCount = 100000;

  explicit TissueAttachment(Settings settings);
  /// "from", "to": the abscissa span (default the whole curve, from < to); "count": points
  /// (1 .. 100000, default 10); "stiffness" (N/m per metre, > 0); "damping" (N·s/m per metre,
  /// >= 0, default 0); "anchors": "initial" (default) or "root" with "root": {"from", "to"}
  /// (m); "rest_length": metres >= 0 (default 0) or "initial".
  static std::unique_ptr<TissueAttachment> fromParams(const Params& p);

  std::string typeName() const override { return "TissueAttachment"; }
  void addForce(const SceneState& s, VecX& B) const override;
  double potentialEnergy(const SceneState& s) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }

  int count() const { return settings_.count; }
  double abscissa(int i) const { return abscissas_[i]; }
  const Vec3& anchor(int i) const { return anchors_[i]; }
  /// k_i and c_i of each point (after init).
  double pointStiffness() const { return point_stiffness_; }
  double pointDamping() const { return point_damping_; }
  /// The spring's force on the curve at point i in state s (N): −k_i (1 − r_i/|d_i|) d_i, taut only.
  Vec3 springForce(const SceneState& s, int i) const;
  /// The sum over the points of |spring force| (N): how hard the tissue pulls on its organ.
  double totalTension(const SceneState& s) const;

 private:
  void init(const Scene& scene) override;
  /// The points' abscissas, anchors and rest lengths from the configuration q at the start.
  void placePoints(const VecX& q);

  Settings settings_;
  const CurveBody* curve_ = nullptr;
  std::vector<double> abscissas_, rest_lengths_;
  std::vector<Vec3> anchors_;
  std::vector<BodyPoint> points_;  // the attached points, at abscissas_: their forces go up through them
  double point_stiffness_ = 0.0, point_damping_ = 0.0;
};

}  // namespace filum::mechanics
