// StylusScript: where a scripted stylus is, and which buttons it holds, at each time — the
// trajectory of a ScriptedDevice, or the target a SimulatedDevice's hand pulls toward.
//
//   "waypoints": [{"time": t, "position": [x, y, z], "buttons": b, "roll": rad}, ...]
//                          (device frame, m, s; "roll", the stylus turned about its own axis,
//                          defaults to the previous waypoint's, 0 at the first)
//   "csv": "file.csv"      the same as rows "time,x,y,z[,buttons[,roll]]" (a header line is
//                          allowed; a row without a roll keeps the previous row's), relative to
//                          the scene file
//   "interpolation": "linear" | "smooth"   between waypoints (geometry::ScriptedPath)
// Buttons hold from their waypoint until the next (bit 0: the first button, the grasper's
// jaws by default); "buttons" may be omitted (0). At most kMaxWaypoints, times increasing.
#pragma once

#include <string>
#include <vector>

#include "filum/core/params.hpp"
#include "filum/geometry/scripted_path.hpp"

namespace filum::haptics {

/// A script of 1e6 waypoints is 17 minutes at 1 kHz: beyond, a recording, not a script.
inline constexpr int kMaxWaypoints = 1000000;

class StylusScript {
 public:
  StylusScript() = default;
  /// Waypoints with times strictly increasing (>= 0) and the buttons held from each.
  /// `rolls`: the stylus's roll at each waypoint (rad; empty: 0 throughout).
  StylusScript(std::vector<geometry::ScriptedPath::Keyframe> keyframes, std::vector<unsigned> buttons,
               geometry::ScriptedPath::Interpolation interpolation, std::vector<double> rolls = {});
  /// Reads "waypoints" or "csv" (exactly one) and "interpolation" from p; throws SceneError at
  /// the faulty entry (file:line for a CSV).
  static StylusScript fromParams(const Params& p);

  Vec3 position(double t) const { return path_.position(t); }
  Vec3 velocity(double t) const { return path_.velocity(t); }
  unsigned buttons(double t) const;
  /// The roll (rad), interpolated as the position is.
  double roll(double t) const { return roll_path_.position(t).x(); }
  /// Time of the last waypoint (s).
  double endTime() const { return times_.empty() ? 0.0 : times_.back(); }

 private:
  geometry::ScriptedPath path_;
  geometry::ScriptedPath roll_path_;  // the roll as the x coordinate of a path
  std::vector<double> times_;
  std::vector<unsigned> buttons_;
};

}  // namespace filum::haptics
