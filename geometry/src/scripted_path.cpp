#include "filum/geometry/scripted_path.hpp"

#include <algorithm>
#include <stdexcept>

namespace filum::geometry {

ScriptedPath::ScriptedPath(std::vector<Keyframe> keyframes, Interpolation interpolation)
    : keyframes_(std::move(keyframes)), interpolation_(interpolation) {
  for (std::size_t k = 1; k < keyframes_.size(); ++k)
    if (!(keyframes_[k].time > keyframes_[k - 1].time))
      throw std::invalid_argument("ScriptedPath: keyframe times must increase strictly");
}

ScriptedPath ScriptedPath::fromParams(const Params& p, const std::string& key) {
  std::vector<Keyframe> keyframes;
  const std::vector<Params> items = p.objects({key, "s, m"});  // keyframes: time, position
  if (items.empty()) p.fail(key, "at least one keyframe {\"time\": t, \"position\": [x, y, z]}");
  for (const Params& item : items) {
    const double time = item.number({"time", "s"});
    if (time < 0.0) item.fail("time", "a time >= 0 (s)");
    if (!keyframes.empty() && !(time > keyframes.back().time))
      item.fail("time", "a time later than the previous keyframe's (" + describeJson(keyframes.back().time) + " s)");
    keyframes.push_back({time, item.vec3({"position", "m"})});
    item.finish();
  }
  Interpolation interpolation = Interpolation::kLinear;
  const std::string name = p.string("interpolation", "linear");
  if (name == "smooth") {
    interpolation = Interpolation::kSmooth;
  } else if (name != "linear") {
    p.fail("interpolation", "\"linear\" or \"smooth\"");
  }
  return ScriptedPath(std::move(keyframes), interpolation);
}

int ScriptedPath::segment(double t) const {
  // Binary search: a stylus script read from a recording holds up to 1e6 keyframes, looked up
  // at every servo tick (haptics/stylus_script.hpp).
  const auto after = std::upper_bound(keyframes_.begin(), keyframes_.end(), t,
                                      [](double time, const Keyframe& k) { return time < k.time; });
  return static_cast<int>(after - keyframes_.begin()) - 1;
}

Vec3 ScriptedPath::tangent(int k) const {
  const int last = static_cast<int>(keyframes_.size()) - 1;
  if (k <= 0 || k >= last) return Vec3::Zero();
  return (keyframes_[k + 1].position - keyframes_[k - 1].position) / (keyframes_[k + 1].time - keyframes_[k - 1].time);
}

Vec3 ScriptedPath::position(double t) const {
  const int k = segment(t);
  if (k < 0) return keyframes_.front().position;
  if (k + 1 >= static_cast<int>(keyframes_.size())) return keyframes_.back().position;
  const Keyframe& a = keyframes_[k];
  const Keyframe& b = keyframes_[k + 1];
  const double h = b.time - a.time;
  const double u = (t - a.time) / h;
  if (interpolation_ == Interpolation::kLinear) return (1.0 - u) * a.position + u * b.position;
  const double u2 = u * u, u3 = u2 * u;
  return (2 * u3 - 3 * u2 + 1) * a.position + (u3 - 2 * u2 + u) * h * tangent(k) + (-2 * u3 + 3 * u2) * b.position +
         (u3 - u2) * h * tangent(k + 1);
}

Vec3 ScriptedPath::velocity(double t) const {
  const int k = segment(t);
  if (k < 0 || k + 1 >= static_cast<int>(keyframes_.size())) return Vec3::Zero();
  const Keyframe& a = keyframes_[k];
  const Keyframe& b = keyframes_[k + 1];
  const double h = b.time - a.time;
  if (interpolation_ == Interpolation::kLinear) return (b.position - a.position) / h;
  const double u = (t - a.time) / h, u2 = u * u;
  return ((6 * u2 - 6 * u) * a.position + (3 * u2 - 4 * u + 1) * h * tangent(k) + (-6 * u2 + 6 * u) * b.position +
          (3 * u2 - 2 * u) * h * tangent(k + 1)) /
         h;
}

Vec3 ScriptedPath::acceleration(double t) const {
  const int k = segment(t);
  if (interpolation_ == Interpolation::kLinear || k < 0 || k + 1 >= static_cast<int>(keyframes_.size()))
    return Vec3::Zero();
  const Keyframe& a = keyframes_[k];
  const Keyframe& b = keyframes_[k + 1];
  const double h = b.time - a.time;
  const double u = (t - a.time) / h;
  return ((12 * u - 6) * a.position + (6 * u - 4) * h * tangent(k) + (-12 * u + 6) * b.position +
          (6 * u - 2) * h * tangent(k + 1)) /
         (h * h);
}

}  // namespace filum::geometry
