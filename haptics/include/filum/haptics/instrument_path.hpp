// InstrumentPath: an instrument driven by a script — its pose and jaw opening over time, from
// keyframes, at rest before the first and after the last:
//   "path": [{"time": t, "position": [x, y, z], "direction": [dx, dy, dz], "roll": r, "jaw": o}, ...]
// position: the jaws' hinge (m); direction: the shaft's axis towards the tip; roll: the turn of
// the jaws' plane about it (rad, instrument_shape.hpp); jaw: the opening o in [0, 1] (0 closed).
// direction, roll and jaw default to the previous keyframe's (the first's: roll 0, jaw 0); the
// first keyframe needs a direction.
// Interpolation, all C1 in time:
//   position: cubic Hermite per coordinate with the monotone velocities of Fritsch & Butland
//             ("A method for constructing local monotone piecewise cubic interpolants", SIAM J.
//             Sci. Stat. Comput. 5 (1984) 300): at keyframe k, with the chords' slopes δ₀, δ₁ and
//             the intervals h₀, h₁ on either side,
//               m_k = 3 (h₀ + h₁) / ((2h₁ + h₀)/δ₀ + (h₁ + 2h₀)/δ₁)  if δ₀ δ₁ > 0, else 0,
//             and 0 at the first and last keyframes. The hand moves through keyframes on one
//             straight run without stopping, but never overshoots one: a pause (two equal
//             keyframes) is a true stop, and a straight move stays on its segment (Catmull-Rom's
//             velocities would carry the jaws past a keyframe before a pause);
//   rotation: q(t) = slerp(q_k, q_{k+1}, σ(u)), σ(u) = 3u² − 2u³ (the shortest turn between the
//             keyframes' frames, starting and ending at rest);
//   jaw:      o(t) = o_k + (o_{k+1} − o_k) σ(u).
#pragma once

#include <vector>

#include <Eigen/Geometry>

#include "filum/core/params.hpp"
#include "filum/haptics/instrument_shape.hpp"

namespace filum::haptics {

class InstrumentPath {
 public:
  struct Keyframe {
    double time = 0.0;
    Vec3 position = Vec3::Zero();
    Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
    double jaw = 0.0;
  };

  InstrumentPath() = default;
  /// Keyframes with strictly increasing times (at least one).
  explicit InstrumentPath(std::vector<Keyframe> keyframes);
  /// From p[key] (see above); throws SceneError at the faulty keyframe. With a trocar `port`,
  /// the keyframes take no direction: the shaft's axis runs from the port to the hinge.
  static InstrumentPath fromParams(const Params& p, const std::string& key, const Vec3* port = nullptr);

  InstrumentPose pose(double t) const;
  /// The hinge at t.
  Vec3 hinge(double t) const { return position(t); }
  double jaw(double t) const;
  double endTime() const { return keyframes_.back().time; }

 private:
  /// Segment k holding t and σ(u) in it; k = −1 before the first keyframe, size − 1 after the last.
  int segment(double t, double& sigma) const;
  /// The hinge at t (cubic Hermite on the segment holding it).
  Vec3 position(double t) const;
  std::vector<Keyframe> keyframes_;
  std::vector<Vec3> velocities_;  // m_k per keyframe (Fritsch–Butland)
};

}  // namespace filum::haptics
