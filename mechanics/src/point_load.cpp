#include "filum/mechanics/point_load.hpp"

#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::mechanics {

PointLoad::PointLoad(double abscissa, std::vector<Keyframe> keyframes)
    : abscissa_(abscissa), keyframes_(std::move(keyframes)) {}

std::unique_ptr<PointLoad> PointLoad::fromParams(const Params& p) {
  const double s = p.abscissa("abscissa");
  std::vector<Keyframe> keyframes;
  if (p.has({"path", "s, N, N·m"})) {
    if (p.has({"force", "N"}) || p.has({"torque", "N·m"})) p.fail("path", "either 'path' or a constant 'force'/'torque', not both");
    for (const Params& key : p.objects({"path", "s, N, N·m"})) {
      Keyframe k{key.nonNegative({"time", "s"}, -1.0), key.vec3({"force", "N"}, Vec3::Zero()), key.vec3({"torque", "N·m"}, Vec3::Zero())};
      if (k.time < 0.0) key.fail("time", "a time >= 0 (s)");
      if (!keyframes.empty() && k.time <= keyframes.back().time)
        key.fail("time", "a time later than the keyframe before (" + std::to_string(keyframes.back().time) + " s)",
                 std::to_string(k.time));
      key.finish();
      keyframes.push_back(k);
    }
    if (keyframes.empty()) p.fail("path", "at least one keyframe {\"time\", \"force\", \"torque\"}", "an empty list");
  } else {
    if (!p.has({"force", "N"}) && !p.has({"torque", "N·m"})) p.fail("force", "a 'force' (N) or a 'torque' (N·m), or a 'path' of them");
    keyframes.push_back({0.0, p.vec3({"force", "N"}, Vec3::Zero()), p.vec3({"torque", "N·m"}, Vec3::Zero())});
  }
  for (const Keyframe& k : keyframes)
    if (!k.force.allFinite() || !k.torque.allFinite()) p.fail(p.has({"path", "s, N, N·m"}) ? "path" : "force", "finite loads");
  return std::make_unique<PointLoad>(s, std::move(keyframes));
}

void PointLoad::init(const Scene&) {
  curve_ = body().curve();
  if (!curve_) throw SceneError(origin(), "a curve body for " + describe(), body().describe());
  point_.attach(*curve_, abscissa_);
  bool torque = false;
  for (const Keyframe& k : keyframes_) torque = torque || k.torque != Vec3::Zero();
  if (torque && !curve_->takesTorques())
    throw SceneError(origin(), "a body with material frames (a FramedChain) for a torque",
                     body().describe() + ", whose control points take forces only");
}

PointLoad::Keyframe PointLoad::loadAt(double t) const {
  if (t <= keyframes_.front().time) return keyframes_.front();
  if (t >= keyframes_.back().time) return keyframes_.back();
  std::size_t k = 1;
  while (keyframes_[k].time < t) ++k;
  const Keyframe &a = keyframes_[k - 1], &b = keyframes_[k];
  const double u = (t - a.time) / (b.time - a.time);
  return {t, (1.0 - u) * a.force + u * b.force, (1.0 - u) * a.torque + u * b.torque};
}

void PointLoad::addForce(const SceneState& s, VecX& B) const {
  const Keyframe load = loadAt(s.time);
  point_.addForce(load.force, B);  // Q_j += b_j(s) F
  if (load.torque != Vec3::Zero()) curve_->addTorque(s, abscissa_, load.torque, B);
}

double PointLoad::potentialEnergy(const SceneState& s) const {
  return -loadAt(s.time).force.dot(curve_->position(s.q, abscissa_));
}

}  // namespace filum::mechanics
