#include "filum/haptics/needle.hpp"

#include <cmath>

namespace filum::haptics {

Needle::Settings Needle::settingsFromParams(const Params& p) {
  Settings s;
  s.name = p.string("name");
  s.radius = p.positive({"radius", "m"}, s.radius);
  s.arc = p.positive({"arc", "rad"}, s.arc);
  // Beyond a full turn the wire would overlap itself.
  if (s.arc > 2.0 * M_PI) p.fail("arc", "an angle in (0, 2π] (rad; 3/8 of a circle is 2.356)");
  s.wire_radius = p.positive({"wire_radius", "m"}, s.wire_radius);
  if (s.wire_radius >= s.radius) p.fail("wire_radius", "a wire radius below the needle's radius (" + describeJson(s.radius) + " m)");
  const Vec3 w = p.vec3({"normal", "1"});
  if (!(w.norm() > 0.0)) p.fail("normal", "a non-zero vector (normal to the needle's plane)");
  const Vec3 start = p.vec3({"start", "m"});
  const Vec3 n = w.normalized();
  const Vec3 u = start - start.dot(n) * n;
  if (!(u.norm() > 1e-9 * start.norm()) || !(start.norm() > 0.0))
    p.fail("start", "a direction from the centre to the swage, not along the normal");
  s.pose.position = p.vec3({"center", "m"});
  s.pose.rotation.col(0) = u.normalized();
  s.pose.rotation.col(2) = n;
  s.pose.rotation.col(1) = n.cross(u.normalized());
  s.thread = p.string("thread", "");
  s.abscissa = p.has("thread") ? p.abscissa("abscissa") : 0.0;
  s.stiffness = p.positive({"stiffness", "N/m"}, s.stiffness);
  p.finish();
  return s;
}

Needle::Needle(Settings settings) : settings_(std::move(settings)), pose_(settings_.pose) {
  swage_hold_->touching = false;
  swage_hold_->grasp_stiffness = settings_.stiffness;
  swage_hold_->position = swage(pose_);
  swage_lead_hold_->touching = false;
  swage_lead_hold_->grasp_stiffness = settings_.stiffness;
  swage_lead_hold_->position = swageLead(pose_);
}

Vec3 Needle::point(const RigidPose& pose, double theta) const {
  return pose.apply(settings_.radius * Vec3(std::cos(theta), std::sin(theta), 0.0));
}

void Needle::move(const RigidPose& now, const RigidPose& next, double t, double h) {
  pose_ = now;
  swage_hold_->position = swage(now);
  swage_hold_->velocity = (swage(next) - swage_hold_->position) / h;
  swage_hold_->time = t;
  swage_lead_hold_->position = swageLead(now);
  swage_lead_hold_->velocity = (swageLead(next) - swage_lead_hold_->position) / h;
  swage_lead_hold_->time = t;
}

Vec3 Needle::swageLead(const RigidPose& pose) const {
  // T(0) = dP/dθ / R at θ = 0: the direction v of the needle's frame, turned by the pose.
  return swage(pose) - kSwageLead * (pose.rotation * Vec3::UnitY());
}

}  // namespace filum::haptics
