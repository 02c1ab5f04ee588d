#include "filum/haptics/hub_control.hpp"

#include <algorithm>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/constraints/target_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/node.hpp"
#include "filum/mechanics/rod_end_frame.hpp"

namespace filum::haptics {

std::unique_ptr<HubControl> HubControl::find(Scene& scene, const std::string& path) {
  Node* node = scene.root().find(path);
  if (!node || !node->mechanicalState() || !node->mechanicalState()->curve()) return nullptr;
  std::unique_ptr<HubControl> hub(new HubControl());
  hub->name_ = path;
  for (const auto& c : node->components())
    if (auto* point = dynamic_cast<constraints::ProjectedPointConstraint*>(c.get()); point && point->abscissa() == 0.0)
      hub->hub_ = point;
  hub->frame_ = mechanics::RodEndFrame::atStartOf(*node);  // the hub's, not a held tip's
  if (!hub->hub_) return nullptr;
  // The introducer's axis: the hub's tangent now (at the start, before any push).
  const CurveBody& body = *node->mechanicalState()->curve();
  const Vec3 tangent = body.tangent(scene.state().q, 0.0);
  hub->axis_ = tangent.norm() > 0.0 ? Vec3(tangent.normalized()) : Vec3::UnitZ();
  hub->start_ = hub->hub_->target().position(scene.state());
  return hub;
}

void HubControl::push(Scene& scene, double distance, double duration) {
  const SceneState& now = scene.state();
  // From where the target is now to the goal: the last stroke's goal moved on by `distance` when
  // a stroke is under way (a double press moves twice the stroke).
  const Vec3 from = hub_->target().position(now);
  goal_ = (push_end_ >= 0.0 ? goal_ : from) + distance * axis_;
  push_end_ = now.time + duration;
  constraints::steerTarget(*hub_, now, from, (goal_ - from) / duration);
}

bool HubControl::turn(const Scene& scene, double angle, double duration) {
  if (!frame_) return false;
  frame_->turn(angle, scene.state().time, scene.state().time + duration);
  return true;
}

void HubControl::update(Scene& scene) {
  if (push_end_ < 0.0 || scene.state().time < push_end_) return;
  constraints::steerTarget(*hub_, scene.state(), goal_, Vec3::Zero());
  push_end_ = -1.0;
}

void HubControl::steer(Scene& scene, double insertion, double speed) {
  push_end_ = -1.0;
  constraints::steerTarget(*hub_, scene.state(), start_ + insertion * axis_, speed * axis_);
}

bool HubControl::rollTo(const Scene& scene, double roll, double duration) {
  if (!frame_) return false;
  const double now = scene.state().time;
  frame_->turn(roll - frame_->roll(now), now, now + duration);
  return true;
}

double HubControl::insertion(const Scene& scene) const {
  return (hub_->target().position(scene.state()) - start_).dot(axis_);
}

double HubControl::roll(const Scene& scene) const { return frame_ ? frame_->roll(scene.state().time) : 0.0; }

Vec3 HubControl::force(const Scene& scene) const {
  const Eigen::Ref<const VecX> lambda = scene.constraintMultipliers(*hub_);
  Vec3 f = Vec3::Zero();
  for (Eigen::Index i = 0; i < lambda.size(); ++i) f += lambda[i] * hub_->directions()[i];
  return f;
}

double HubControl::torque(const Scene& scene) const {
  return frame_ ? frame_->torqueOnRod(scene.state()).dot(axis_) : 0.0;
}

}  // namespace filum::haptics
