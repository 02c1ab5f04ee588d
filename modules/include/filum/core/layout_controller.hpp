// LayoutController: a body component that changes its body's control points as the run goes —
// adaptive refinement (mechanics/adaptive_refinement.hpp: insert where the curve bends or is
// touched, remove where it is straight). Before a step (Scene::beginStep, after the scheduled
// layout changes) the scene asks every controller that is due for a plan and applies it: the
// insertions in one Scene::refine (Oslo insertion: the curve and its velocity kept), then each
// removal by Scene::coarsen (knot removal within the plan's tolerance, linear momentum kept),
// skipping those the curve refuses. Layout changes allocate; steps between them do not.
#pragma once

#include <vector>

#include "filum/core/body_component.hpp"

namespace filum {

class Scene;

class LayoutController : public BodyComponent {
 public:
  struct Plan {
    std::vector<double> insert;  // abscissas in (0, 1) where to insert a knot
    std::vector<double> remove;  // interior knots to remove, each if the curve moves by <= tolerance
    double tolerance = 0.0;      // m
  };
  /// Whether the controller plans before the step that starts at step index `step`.
  virtual bool due(long step) const = 0;
  /// What to insert and remove in the scene's current state (out is cleared first by the scene).
  virtual void plan(const Scene& scene, Plan& out) const = 0;
  /// The curve refused the planned removal of the knot at s (it would move further than the
  /// tolerance): a controller may remember it rather than plan it again at once (an attempt
  /// costs a least-squares fit, and allocates).
  virtual void removalRefused(double /*abscissa*/) {}
};

}  // namespace filum
