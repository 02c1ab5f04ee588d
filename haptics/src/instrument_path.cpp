#include "filum/haptics/instrument_path.hpp"

#include <algorithm>
#include <stdexcept>

#include "filum/core/scene_error.hpp"

namespace filum::haptics {

namespace {

geometry::ScriptedPath positionPath(const std::vector<InstrumentPath::Keyframe>& keyframes) {
  std::vector<geometry::ScriptedPath::Keyframe> points;
  points.reserve(keyframes.size());
  for (const InstrumentPath::Keyframe& k : keyframes) points.push_back({k.time, k.position});
  return geometry::ScriptedPath(std::move(points), geometry::ScriptedPath::Interpolation::kSmooth);
}

}  // namespace

InstrumentPath::InstrumentPath(std::vector<Keyframe> keyframes)
    : keyframes_(std::move(keyframes)), positions_(positionPath(keyframes_)) {
  if (keyframes_.empty()) throw std::invalid_argument("InstrumentPath: at least one keyframe");
}

InstrumentPath InstrumentPath::fromParams(const Params& p, const std::string& key) {
  const std::vector<Params> items = p.objects(key);
  if (items.empty())
    p.fail(key, "at least one keyframe {\"time\": t, \"position\": [x, y, z], \"direction\": [x, y, z], \"jaw\": o}");
  std::vector<Keyframe> keyframes;
  Vec3 direction = Vec3::Zero();
  double roll = 0.0, jaw = 0.0;
  for (const Params& item : items) {
    Keyframe k;
    k.time = item.number("time");
    if (k.time < 0.0) item.fail("time", "a time >= 0 (s)");
    if (!keyframes.empty() && !(k.time > keyframes.back().time))
      item.fail("time", "a time later than the previous keyframe's (" + describeJson(keyframes.back().time) + " s)");
    k.position = item.vec3("position");
    if (keyframes.empty() || item.has("direction")) {
      direction = item.vec3("direction");
      if (!(direction.norm() > 0.0)) item.fail("direction", "a non-zero vector (the shaft's axis towards the tip)");
    }
    roll = item.number("roll", roll);
    jaw = item.number("jaw", jaw);
    if (!(jaw >= 0.0 && jaw <= 1.0)) item.fail("jaw", "an opening in [0, 1] (0: closed, 1: fully open)");
    k.rotation = Eigen::Quaterniond(instrumentFrame(direction, roll));
    // The shorter way round from the previous keyframe's rotation (q and −q are one rotation).
    if (!keyframes.empty() && keyframes.back().rotation.dot(k.rotation) < 0.0) k.rotation.coeffs() *= -1.0;
    k.jaw = jaw;
    item.finish();
    keyframes.push_back(k);
  }
  return InstrumentPath(std::move(keyframes));
}

int InstrumentPath::segment(double t, double& sigma) const {
  const auto after = std::upper_bound(keyframes_.begin(), keyframes_.end(), t,
                                      [](double time, const Keyframe& k) { return time < k.time; });
  const int k = static_cast<int>(after - keyframes_.begin()) - 1;
  sigma = 0.0;
  if (k >= 0 && k + 1 < static_cast<int>(keyframes_.size())) {
    const double u = (t - keyframes_[k].time) / (keyframes_[k + 1].time - keyframes_[k].time);
    sigma = u * u * (3.0 - 2.0 * u);  // σ(u) = 3u² − 2u³
  }
  return k;
}

InstrumentPose InstrumentPath::pose(double t) const {
  double sigma = 0.0;
  const int k = segment(t, sigma);
  Eigen::Quaterniond q;
  if (k < 0) {
    q = keyframes_.front().rotation;
  } else if (k + 1 >= static_cast<int>(keyframes_.size())) {
    q = keyframes_.back().rotation;
  } else {
    q = keyframes_[k].rotation.slerp(sigma, keyframes_[k + 1].rotation);
  }
  InstrumentPose pose;
  pose.hinge = positions_.position(t);
  pose.frame = q.normalized().toRotationMatrix();
  return pose;
}

double InstrumentPath::jaw(double t) const {
  double sigma = 0.0;
  const int k = segment(t, sigma);
  if (k < 0) return keyframes_.front().jaw;
  if (k + 1 >= static_cast<int>(keyframes_.size())) return keyframes_.back().jaw;
  return keyframes_[k].jaw + (keyframes_[k + 1].jaw - keyframes_[k].jaw) * sigma;
}

}  // namespace filum::haptics
