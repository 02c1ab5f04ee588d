// ScriptedPath: a target that moves along keyframes (time, position), linearly between them and
// at rest before the first and after the last. Its acceleration is zero inside each segment;
// the Baumgarte terms of the constraint that follows it absorb the velocity jumps at keyframes.
#pragma once

#include <vector>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::constraints {

class ScriptedPath {
 public:
  struct Keyframe {
    double time;  // s
    Vec3 position;  // m
  };

  ScriptedPath() = default;
  /// Keyframes with strictly increasing times >= 0 (at least one).
  explicit ScriptedPath(std::vector<Keyframe> keyframes);
  /// From [{"time": t, "position": [x, y, z]}, ...] at p[key].
  static ScriptedPath fromParams(const Params& p, const std::string& key);

  bool empty() const { return keyframes_.empty(); }
  Vec3 position(double t) const;
  Vec3 velocity(double t) const;

 private:
  /// Index k of the segment [t_k, t_{k+1}) holding t, or −1 before / size−1 after.
  int segment(double t) const;
  std::vector<Keyframe> keyframes_;
};

}  // namespace filum::constraints
