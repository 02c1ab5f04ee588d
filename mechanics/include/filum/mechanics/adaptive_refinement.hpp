// AdaptiveRefinement: adaptive NUBS at run time ([Lenoir talk 2008]: "adaptive NUBS by Oslo insertion") —
// control points where the thread bends or is held or touched, few where it is straight.
// Every `every` steps, before the step, for each span [b_k, b_k+1] of the curve (its breakpoints)
// in the current state:
//   θ_k  the turning angle of the tangent over the span, Σ_i ∠(P'(σ_i), P'(σ_i+1)) over 4 equal
//        pieces (∫|κ| dl to O(h²) for a smooth span);
//   ℓ_k  its length (chords of the same pieces);
//   touched: a contact, a sliding point, a grasp or a held point lies in it (Scene::actingAbscissas);
// and plans (LayoutController):
//   insert a knot at the middle of every span with θ_k > refine_angle, or touched and longer than
//     min_span — largest θ first, while the count stays within max_points;
//   remove every interior knot whose two spans are both straight (θ < coarsen_angle), untouched,
//     not next to a cut, and not next to a knot removed in this plan — while the count stays
//     above min_points, each only if the curve moves by at most `tolerance` there (Scene::coarsen,
//     which also keeps the linear momentum). A knot whose removal was refused is not planned
//     again until the layout changes or its spans have straightened to half the turning they had
//     then (a thread at rest plans nothing, and allocates nothing).
// Hysteresis: coarsen_angle <= refine_angle / 4, so the halves of a span just split (θ/2 each,
// above refine_angle/2) are not merged again at the next plan.
// Insertion (Scene::refine) keeps the curve and its velocity field exactly (to round-off).
#pragma once

#include <memory>
#include <vector>

#include "filum/core/layout_controller.hpp"
#include "filum/core/params.hpp"

namespace filum {
class CurveBody;
}

namespace filum::mechanics {

class AdaptiveRefinement final : public LayoutController {
 public:
  struct Settings {
    int every = 10;                 // steps between plans
    double refine_angle = 0.25;     // rad
    double coarsen_angle = 0.03;    // rad
    double min_span = 0.0;          // m: touched spans are refined down to this length (0: not)
    double tolerance = 1e-5;        // m: removal error bound
    int max_points = 0;             // 0: twice the initial count
    int min_points = 0;             // 0: the initial count
  };
  explicit AdaptiveRefinement(Settings settings) : settings_(settings) {}
  /// "every" (steps >= 1, default 10), "refine_angle" (rad, (0, π], default 0.25),
  /// "coarsen_angle" (rad, [0, refine_angle/4], default 0.03), "min_span" (m >= 0, default 0),
  /// "tolerance" (m > 0, default 1e-5), "max_points" and "min_points" (counts; defaults: twice
  /// and once the body's initial count).
  static std::unique_ptr<AdaptiveRefinement> fromParams(const Params& p);

  std::string typeName() const override { return "AdaptiveRefinement"; }
  bool due(long step) const override { return step % settings_.every == 0; }
  void plan(const Scene& scene, Plan& out) const override;
  void removalRefused(double abscissa) override;
  const Settings& settings() const { return settings_; }
  int maxPoints() const { return max_points_; }
  int minPoints() const { return min_points_; }

 private:
  void init(const Scene& scene) override;
  /// Breakpoints and cuts of the curve, kept while its layout does not change (no allocation
  /// in a plan that changes nothing).
  void refreshLayout() const;

  Settings settings_;
  const CurveBody* curve_ = nullptr;
  int max_points_ = 0, min_points_ = 0;
  mutable long layout_revision_ = -1;
  mutable std::vector<double> breakpoints_, cuts_, angles_, lengths_, acting_;
  mutable std::vector<char> touched_, removed_;
  mutable std::vector<int> order_;
  // Knots whose removal was refused at this layout, with the turning of their two spans then.
  mutable std::vector<std::pair<double, double>> refused_;
  mutable std::vector<std::pair<double, double>> planned_turning_;  // (knot, θ_{j−1} + θ_j) planned now
};

}  // namespace filum::mechanics
