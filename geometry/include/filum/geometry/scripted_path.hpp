// ScriptedPath: a target that moves along keyframes (time, position), at rest before the first
// and after the last. Two interpolations:
//   "linear" (default): straight segments at constant speed; Ẍ = 0 inside each segment, and
//     the velocity jumps at keyframes are absorbed by the Baumgarte terms of the constraint
//     that follows it (a transient gap of order Δv/ω);
//   "smooth": cubic Hermite segments with Catmull-Rom velocities m_k = (x_{k+1} − x_{k−1}) /
//     (t_{k+1} − t_{k−1}) and m = 0 at the first and last keyframes — C1 in time, so the
//     constrained point follows without transients; its acceleration Ẍ(t) is exact and goes
//     into the constraint rows. On [t_k, t_{k+1}], h = t_{k+1} − t_k, u = (t − t_k)/h:
//       X = (2u³−3u²+1) x_k + (u³−2u²+u) h m_k + (−2u³+3u²) x_{k+1} + (u³−u²) h m_{k+1}.
#pragma once

#include <vector>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::geometry {

class ScriptedPath {
 public:
  struct Keyframe {
    double time;  // s
    Vec3 position;  // m
  };
  enum class Interpolation { kLinear, kSmooth };

  ScriptedPath() = default;
  /// Keyframes with strictly increasing times >= 0 (at least one).
  explicit ScriptedPath(std::vector<Keyframe> keyframes, Interpolation interpolation = Interpolation::kLinear);
  /// From [{"time": t, "position": [x, y, z]}, ...] at p[key], and p["interpolation"]:
  /// "linear" (default) or "smooth".
  static ScriptedPath fromParams(const Params& p, const std::string& key);

  bool empty() const { return keyframes_.empty(); }
  Interpolation interpolation() const { return interpolation_; }
  Vec3 position(double t) const;
  Vec3 velocity(double t) const;
  /// Ẍ(t): 0 for linear paths (inside segments), exact for smooth ones.
  Vec3 acceleration(double t) const;

 private:
  /// Index k of the segment [t_k, t_{k+1}) holding t, or −1 before / size−1 after.
  int segment(double t) const;
  /// Catmull-Rom velocity at keyframe k (0 at the ends).
  Vec3 tangent(int k) const;
  std::vector<Keyframe> keyframes_;
  Interpolation interpolation_ = Interpolation::kLinear;
};

}  // namespace filum::geometry
