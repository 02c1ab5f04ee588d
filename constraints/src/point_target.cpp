#include "filum/constraints/point_target.hpp"

#include <stdexcept>

#include "filum/constraints/curve_lookup.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::constraints {

PointTarget PointTarget::scripted(geometry::ScriptedPath path) {
  PointTarget t(Kind::kScripted, Vec3::Zero());
  t.path_ = std::move(path);
  return t;
}

PointTarget PointTarget::attached(std::string object, double abscissa) {
  PointTarget t(Kind::kAttached, Vec3::Zero());
  t.object_ = std::move(object);
  t.abscissa_ = abscissa;
  return t;
}

PointTarget PointTarget::fromParams(const Params& p) {
  const bool has_target = p.has("target");
  const bool has_path = p.has({"path", "s, m"});
  if (has_target && has_path) p.fail("path", "either 'target' or 'path', not both");
  if (has_path) return scripted(geometry::ScriptedPath::fromParams(p, "path"));
  if (!has_target) return PointTarget();
  if (p.raw({"target", "m"}).is_object()) {
    const Params attach = p.object("target");
    PointTarget t = attached(attach.string("object"), attach.abscissa("abscissa"));
    if (t.object_.empty()) attach.fail("object", "the path of the node holding the target spline");
    t.offset_ = attach.vec3({"offset", "m"}, Vec3::Zero());
    t.where_ = attach.where("object");
    attach.finish();
    return t;
  }
  return fixed(p.vec3({"target", "m"}));
}

void PointTarget::init(const Scene& scene, const Component& owner, const Vec3& start, const MechanicalState& own_body,
                       double own_abscissa) {
  if (kind_ == Kind::kStart) position_ = start;
  if (kind_ != Kind::kAttached) return;
  const CurveBody& body = findCurve(scene, object_, where_, owner);
  if (&body == &own_body && abscissa_ == own_abscissa)
    throw SceneError(where_, "another point than the constrained one (" + owner.describe() +
                                 " would hold a point to itself: g ≡ 0, a singular system)",
                     "the same body at the same abscissa " + describeJson(abscissa_));
  point_.attach(body, abscissa_);
}

bool PointTarget::steer(const Vec3& position, const Vec3& velocity, double t0) {
  if (kind_ == Kind::kAttached) return false;
  kind_ = Kind::kSteered;
  position_ = position;
  velocity_ = velocity;
  steered_at_ = t0;
  path_ = geometry::ScriptedPath();
  return true;
}

Vec3 PointTarget::position(const SceneState& s) const {
  switch (kind_) {
    case Kind::kScripted:
      return path_.position(s.time);
    case Kind::kSteered:
      return position_ + velocity_ * (s.time - steered_at_);
    case Kind::kAttached:
      return point_.map(s.q) + offset_;
    default:
      return position_;
  }
}

Vec3 PointTarget::velocity(const SceneState& s) const {
  switch (kind_) {
    case Kind::kScripted:
      return path_.velocity(s.time);
    case Kind::kAttached:
      return point_.map(s.v);
    case Kind::kSteered:
      return velocity_;
    default:
      return Vec3::Zero();
  }
}

Vec3 PointTarget::knownAcceleration(const SceneState& s) const {
  return kind_ == Kind::kScripted ? path_.acceleration(s.time) : Vec3::Zero();
}

Vec3 PointTarget::attachedAcceleration(const VecX& a) const {
  if (kind_ != Kind::kAttached) return Vec3::Zero();
  return point_.map(a);
}

Vec3 PointTarget::positionAt(double t) const {
  if (kind_ == Kind::kAttached) throw std::logic_error("PointTarget::positionAt: an attached target needs a state");
  if (kind_ == Kind::kSteered) return position_ + velocity_ * (t - steered_at_);
  return kind_ == Kind::kScripted ? path_.position(t) : position_;
}

void PointTarget::addToAnchor(ConstraintRows& rows, double scale) const {
  if (kind_ != Kind::kAttached) return;
  point_.forEachWeight([&](int point, double weight) { rows.addAnchorPoint(point, -scale * weight); });
}

bool PointTarget::reattach(double abscissa, const Vec3& offset) {
  if (kind_ != Kind::kAttached) return false;
  abscissa_ = abscissa;
  offset_ = offset;
  point_.moveTo(abscissa);
  return true;
}

void PointTarget::addReaction(const Vec3& F, VecX& B) const {
  if (kind_ != Kind::kAttached) return;
  point_.addForce(F, B, -1.0);
}

}  // namespace filum::constraints
