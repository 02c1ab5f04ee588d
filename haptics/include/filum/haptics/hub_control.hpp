// HubControl: the hand at an instrument's hub — the proximal end (s = 0) of a catheter or
// guidewire held at the introducer by a point constraint (FixedPointConstraint) and, for a rod,
// turned by a RodEndFrame. Keys in `filum view` push or pull it along the introducer's axis (the
// hub's initial tangent a₀) and turn it about the shaft: each press a move of `distance` or
// `angle` done at constant speed over `duration`, then held, as a hand feeds a wire in short
// strokes. The position goes through the constraint's steered target
// (constraints/target_constraint.hpp: X(t) = X₀ + v (t − t₀)), the roll through
// RodEndFrame::turn; the scene's scripted paths for them are dropped from the first press on.
// A haptic device drives the same hub continuously (hub_device.hpp: steer, rollTo) and feels what
// it takes (force, torque).
#pragma once

#include <memory>
#include <string>

#include "filum/core/scene.hpp"

namespace filum::constraints {
class ProjectedPointConstraint;
}
namespace filum::mechanics {
class RodEndFrame;
}

namespace filum::haptics {

class HubControl {
 public:
  /// The hub of the instrument at node `path`: its point constraint at s = 0 (required) and its
  /// RodEndFrame at the start (optional: a thread cannot be turned). nullptr when the node has no
  /// point constraint at s = 0.
  static std::unique_ptr<HubControl> find(Scene& scene, const std::string& path);

  /// Pushes the hub by `distance` (m; negative pulls) along a₀ from time t over `duration` (s).
  void push(Scene& scene, double distance, double duration);
  /// Turns it by `angle` (rad, right-handed about a₀) from now over `duration`; false without a
  /// RodEndFrame.
  bool turn(const Scene& scene, double angle, double duration);
  /// Holds the hub where a push ended once its time is past: call between steps.
  void update(Scene& scene);

  /// The hub held at `insertion` (m along a₀ from where it started) now and moving on at `speed`
  /// (m/s): the hand's stroke as a device reads it. Ends a key's push.
  void steer(Scene& scene, double insertion, double speed);
  /// The hub turned to `roll` (rad) over `duration` (s) from now; false without a RodEndFrame.
  bool rollTo(const Scene& scene, double roll, double duration);
  /// How far the hub's target is along a₀ from where it started (m), and the roll it holds (rad;
  /// 0 without a RodEndFrame).
  double insertion(const Scene& scene) const;
  double roll(const Scene& scene) const;
  /// The force the hub's point constraint put on the instrument in the last constraint solve,
  /// Σ λ_i d_i (N, zero before any): along a₀ the hand's push, across it the introducer's hold.
  Vec3 force(const Scene& scene) const;
  /// The torque the hub's RodEndFrame puts on the instrument about a₀ (N·m; 0 without one).
  double torque(const Scene& scene) const;

  const std::string& name() const { return name_; }
  bool turns() const { return frame_ != nullptr; }
  const Vec3& axis() const { return axis_; }

 private:
  std::string name_;
  constraints::ProjectedPointConstraint* hub_ = nullptr;
  mechanics::RodEndFrame* frame_ = nullptr;
  Vec3 axis_ = Vec3::UnitZ();
  Vec3 start_ = Vec3::Zero();  // the hub's target at the start (insertion 0)
  Vec3 goal_ = Vec3::Zero();  // where the current push ends
  double push_end_ = -1.0;    // s; < 0: no push under way
};

}  // namespace filum::haptics
