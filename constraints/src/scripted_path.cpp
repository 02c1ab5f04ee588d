#include "filum/constraints/scripted_path.hpp"

#include <stdexcept>

namespace filum::constraints {

ScriptedPath::ScriptedPath(std::vector<Keyframe> keyframes) : keyframes_(std::move(keyframes)) {
  for (std::size_t k = 1; k < keyframes_.size(); ++k)
    if (!(keyframes_[k].time > keyframes_[k - 1].time))
      throw std::invalid_argument("ScriptedPath: keyframe times must increase strictly");
}

ScriptedPath ScriptedPath::fromParams(const Params& p, const std::string& key) {
  std::vector<Keyframe> keyframes;
  const std::vector<Params> items = p.objects(key);
  if (items.empty()) p.fail(key, "at least one keyframe {\"time\": t, \"position\": [x, y, z]}");
  for (const Params& item : items) {
    const double time = item.number("time");
    if (time < 0.0) item.fail("time", "a time >= 0 (s)");
    if (!keyframes.empty() && !(time > keyframes.back().time))
      item.fail("time", "a time later than the previous keyframe's (" + describeJson(keyframes.back().time) + " s)");
    keyframes.push_back({time, item.vec3("position")});
    item.finish();
  }
  return ScriptedPath(std::move(keyframes));
}

int ScriptedPath::segment(double t) const {
  if (t < keyframes_.front().time) return -1;
  for (std::size_t k = 0; k + 1 < keyframes_.size(); ++k)
    if (t < keyframes_[k + 1].time) return static_cast<int>(k);
  return static_cast<int>(keyframes_.size()) - 1;
}

Vec3 ScriptedPath::position(double t) const {
  const int k = segment(t);
  if (k < 0) return keyframes_.front().position;
  if (k + 1 >= static_cast<int>(keyframes_.size())) return keyframes_.back().position;
  const Keyframe& a = keyframes_[k];
  const Keyframe& b = keyframes_[k + 1];
  const double w = (t - a.time) / (b.time - a.time);
  return (1.0 - w) * a.position + w * b.position;
}

Vec3 ScriptedPath::velocity(double t) const {
  const int k = segment(t);
  if (k < 0 || k + 1 >= static_cast<int>(keyframes_.size())) return Vec3::Zero();
  const Keyframe& a = keyframes_[k];
  const Keyframe& b = keyframes_[k + 1];
  return (b.position - a.position) / (b.time - a.time);
}

}  // namespace filum::constraints
