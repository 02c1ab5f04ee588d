#include "filum/mechanics/rod_end_frame.hpp"

#include "filum/core/node.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/chain_elasticity.hpp"
#include "filum/mechanics/framed_chain.hpp"

namespace filum::mechanics {

namespace {

/// "direction" (optional, normalized) and "roll" of p.
RodEndFrame::Keyframe poseFromParams(const Params& p) {
  RodEndFrame::Keyframe k;
  if (p.has({"direction", "1"})) {
    const Vec3 d = p.vec3({"direction", "1"});
    if (!(d.norm() > 0.0)) p.fail("direction", "a non-zero direction");
    k.direction = d.normalized();
  }
  k.roll = p.number({"roll", "rad"}, 0.0);
  return k;
}

}  // namespace

std::unique_ptr<RodEndFrame> RodEndFrame::fromParams(const Params& p) {
  const std::string end = p.string("end", "start");
  if (end != "start" && end != "end") p.fail("end", "\"start\" or \"end\"", "\"" + end + "\"");
  std::vector<Keyframe> keyframes;
  if (p.has({"path", "s, 1, rad"})) {
    if (p.has({"direction", "1"}) || p.has({"roll", "rad"})) p.fail("path", "either a 'path' or a fixed 'direction'/'roll', not both");
    for (const Params& key : p.objects({"path", "s, 1, rad"})) {
      Keyframe k = poseFromParams(key);
      if (!key.has("time")) key.fail("time", "the keyframe's time (s)");
      k.time = key.nonNegative({"time", "s"}, 0.0);
      if (!keyframes.empty() && k.time <= keyframes.back().time)
        key.fail("time", "a time later than the keyframe before (" + std::to_string(keyframes.back().time) + " s)",
                 std::to_string(k.time));
      if (!keyframes.empty() && k.direction.has_value() != keyframes.front().direction.has_value())
        key.fail("direction", "a direction in every keyframe or in none");
      key.finish();
      keyframes.push_back(k);
    }
    if (keyframes.empty()) p.fail("path", "at least one keyframe {\"time\", \"direction\", \"roll\"}", "an empty list");
  } else {
    keyframes.push_back(poseFromParams(p));
  }
  return std::make_unique<RodEndFrame>(end == "start" ? End::kStart : End::kFinish, std::move(keyframes));
}

RodEndFrame* RodEndFrame::atStartOf(const Node& node) {
  RodEndFrame* found = nullptr;
  for (const auto& c : node.components())
    if (auto* frame = dynamic_cast<RodEndFrame*>(c.get()); frame && frame->end() == End::kStart) found = frame;
  return found;
}

void RodEndFrame::init(const Scene& scene) {
  chain_ = dynamic_cast<const FramedChain*>(&body());
  if (!chain_) throw SceneError(origin(), "a FramedChain body for " + describe(), body().describe());
  const ChainElasticity* elasticity = nullptr;
  for (const ForceField* field : scene.forceFields())
    if (const auto* candidate = dynamic_cast<const ChainElasticity*>(field);
        candidate && candidate->bound() && &candidate->body() == &body())
      elasticity = candidate;
  if (!elasticity)
    throw SceneError(origin(),
                     "a ChainElasticity on " + body().describe() +
                         " listed before this component (the rod's bending and twist stiffness)",
                     "none");
  const bool start = end_ == End::kStart;
  segment_ = start ? 0 : chain_->segmentCount() - 1;
  const double half = 0.5 * chain_->restLength(segment_), length = chain_->restLength(segment_) /
                                                                        (chain_->nodeAbscissa(segment_ + 1) - chain_->nodeAbscissa(segment_));
  stiffness_ = elasticity->bendingTwistingStiffness(segment_) / half;
  rest_ = elasticity->restFromInitial() ? Vec3::Zero()
                                        : (start ? elasticity->restTurn(0.0, half) : elasticity->restTurn(length - half, length));
  initial_ = chain_->initialFrame(segment_);
}

std::pair<Vec3, double> RodEndFrame::poseAt(double t) const {
  const Vec3 tangent = initial_ * Vec3::UnitZ();
  const auto pose = [&](const Keyframe& k) { return std::pair<Vec3, double>{k.direction.value_or(tangent), k.roll}; };
  if (t <= keyframes_.front().time) return pose(keyframes_.front());
  if (t >= keyframes_.back().time) return pose(keyframes_.back());
  std::size_t k = 1;
  while (keyframes_[k].time < t) ++k;
  const auto [da, ra] = pose(keyframes_[k - 1]);
  const auto [db, rb] = pose(keyframes_[k]);
  const double u = (t - keyframes_[k - 1].time) / (keyframes_[k].time - keyframes_[k - 1].time);
  const Vec3 d = (1.0 - u) * da + u * db;
  return {d.norm() > 0.0 ? Vec3(d.normalized()) : db, (1.0 - u) * ra + u * rb};
}

void RodEndFrame::turn(double angle, double t0, double t1) {
  const auto [direction, roll0] = poseAt(t0);
  // A turn of the hand under way goes on to its end roll first (a double press turns twice).
  const double from = turned_ && keyframes_.back().time > t0 ? keyframes_.back().roll : roll0;
  keyframes_ = {Keyframe{t0, direction, roll0}, Keyframe{std::max(t1, t0 + 1e-9), direction, from + angle}};
  turned_ = true;
}

Eigen::Quaterniond RodEndFrame::heldFrame(double t) const {
  const auto [d, roll] = poseAt(t);
  return (Eigen::Quaterniond(Eigen::AngleAxisd(roll, d)) *
          Eigen::Quaterniond::FromTwoVectors(initial_ * Vec3::UnitZ(), d) * initial_)
      .normalized();
}

double RodEndFrame::term(const SceneState& s, VecX* forces, Vec3* body_torque) const {
  const bool start = end_ == End::kStart;
  const Eigen::Quaterniond R = chain_->orientation(s.q, segment_), held = heldFrame(s.time);
  const Vec3 phi = geometry::rotationLog(start ? held.conjugate() * R : R.conjugate() * held);
  const Vec3 moment = stiffness_.cwiseProduct(phi - rest_);  // m = B (φ − φ̄) / ℓ
  if (forces || body_torque) {
    const Vec3 torque = start ? Vec3(-geometry::rightJacobianInverse(phi).transpose() * moment)
                              : Vec3(geometry::leftJacobianInverse(phi).transpose() * moment);
    if (forces) chain_->internalVelocities(*forces).segment<3>(3 * segment_) += torque;
    if (body_torque) *body_torque = torque;
  }
  return 0.5 * (phi - rest_).dot(moment);
}

Vec3 RodEndFrame::torqueOnRod(const SceneState& s) const {
  Vec3 body = Vec3::Zero();
  term(s, nullptr, &body);
  return chain_->orientation(s.q, segment_) * body;  // the end segment's body frame → world
}

void RodEndFrame::addForce(const SceneState& s, VecX& B) const { term(s, &B); }

void RodEndFrame::addJacobian(const SceneState& s, double k_factor, double, JacobianAccumulator& out) const {
  if (k_factor == 0.0) return;
  const bool start = end_ == End::kStart;
  const Eigen::Quaterniond R = chain_->orientation(s.q, segment_), held = heldFrame(s.time);
  const Vec3 phi = geometry::rotationLog(start ? held.conjugate() * R : R.conjugate() * held);
  const Eigen::Matrix3d J = start ? geometry::rightJacobianInverse(phi) : geometry::leftJacobianInverse(phi);
  out.addBlock(chain_->internalGroup(segment_), chain_->internalGroup(segment_),
               -k_factor * (J.transpose() * stiffness_.asDiagonal() * J));
}

double RodEndFrame::potentialEnergy(const SceneState& s) const { return term(s, nullptr); }

}  // namespace filum::mechanics
