#include "filum/haptics/instrument_path.hpp"

#include <algorithm>
#include <stdexcept>

#include "filum/core/scene_error.hpp"

namespace filum::haptics {

InstrumentPath::InstrumentPath(std::vector<Keyframe> keyframes) : keyframes_(std::move(keyframes)) {
  if (keyframes_.empty()) throw std::invalid_argument("InstrumentPath: at least one keyframe");
  const int n = static_cast<int>(keyframes_.size());
  velocities_.assign(n, Vec3::Zero());
  for (int k = 1; k + 1 < n; ++k) {
    const double h0 = keyframes_[k].time - keyframes_[k - 1].time, h1 = keyframes_[k + 1].time - keyframes_[k].time;
    for (int c = 0; c < 3; ++c) {
      const double d0 = (keyframes_[k].position[c] - keyframes_[k - 1].position[c]) / h0;
      const double d1 = (keyframes_[k + 1].position[c] - keyframes_[k].position[c]) / h1;
      if (d0 * d1 > 0.0) velocities_[k][c] = 3.0 * (h0 + h1) / ((2.0 * h1 + h0) / d0 + (h1 + 2.0 * h0) / d1);
    }
  }
}

Vec3 InstrumentPath::position(double t) const {
  double sigma = 0.0;
  const int k = segment(t, sigma);
  if (k < 0) return keyframes_.front().position;
  if (k + 1 >= static_cast<int>(keyframes_.size())) return keyframes_.back().position;
  const double h = keyframes_[k + 1].time - keyframes_[k].time;
  const double u = (t - keyframes_[k].time) / h, u2 = u * u, u3 = u2 * u;
  // X = (2u³−3u²+1) x_k + (u³−2u²+u) h m_k + (−2u³+3u²) x_{k+1} + (u³−u²) h m_{k+1}.
  return (2 * u3 - 3 * u2 + 1) * keyframes_[k].position + (u3 - 2 * u2 + u) * h * velocities_[k] +
         (-2 * u3 + 3 * u2) * keyframes_[k + 1].position + (u3 - u2) * h * velocities_[k + 1];
}

InstrumentPath InstrumentPath::fromParams(const Params& p, const std::string& key, const Vec3* port) {
  const std::vector<Params> items = p.objects({key, "s, m, 1, 1"});  // time, position, direction, jaw
  if (items.empty())
    p.fail(key, "at least one keyframe {\"time\": t, \"position\": [x, y, z], \"direction\": [x, y, z], \"jaw\": o}");
  std::vector<Keyframe> keyframes;
  Vec3 direction = Vec3::Zero();
  double roll = 0.0, jaw = 0.0;
  for (const Params& item : items) {
    Keyframe k;
    k.time = item.number({"time", "s"});
    if (k.time < 0.0) item.fail("time", "a time >= 0 (s)");
    if (!keyframes.empty() && !(k.time > keyframes.back().time))
      item.fail("time", "a time later than the previous keyframe's (" + describeJson(keyframes.back().time) + " s)");
    k.position = item.vec3({"position", "m"});
    if (port) {
      if (item.has("direction"))
        item.fail("direction", "no direction with a trocar (the shaft runs from the port to the hinge)", "one");
      direction = k.position - *port;
      if (!(direction.norm() > 0.0)) item.fail("position", "a hinge away from the trocar's port");
    } else if (keyframes.empty() || item.has("direction")) {
      direction = item.vec3({"direction", "1"});
      if (!(direction.norm() > 0.0)) item.fail("direction", "a non-zero vector (the shaft's axis towards the tip)");
    }
    roll = item.number({"roll", "rad"}, roll);
    jaw = item.number({"jaw", "1"}, jaw);
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
  pose.hinge = position(t);
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
