// Needle: a rigid curved surgical needle — an arc of a circle of radius R over an angle α (3/8 of
// a circle is 135°), of wire radius r_w — with a thread swaged to its back end. A needle holder's
// jaws (instrument.hpp) catch it where they close on its wire and carry it rigidly; let go, it
// stays where it is (it rests in tissue or on a drape: no dynamics of its own); another holder
// may take it over (a regrasp). The thread's end follows the swage through the coupling of
// haptics/tool.hpp (a stiff hold on the thread's point, and a second one 2 mm along the thread that
// keeps it leaving the swage along the needle's axis).
//
//   "needles": [{"name": "needle", "radius": 0.008, "arc": 2.356, "wire_radius": 2.5e-4,
//                "center": [x, y, z], "normal": [x, y, z], "start": [x, y, z],
//                "thread": "suture", "abscissa": 0.0, "stiffness": 2000}]
// Geometry: the arc's centre c, its plane's normal w and the direction u from c to the swage
// (projected ⊥ w): P(θ) = c + R (cos θ u + sin θ v), v = w × u; the swage at θ = 0, the tip at θ = α.
#pragma once

#include <memory>
#include <string>

#include "filum/core/params.hpp"
#include "filum/haptics/instrument_shape.hpp"
#include "filum/haptics/tool.hpp"

namespace filum::haptics {

/// A rigid placement: x_world = position + rotation · x_local.
struct RigidPose {
  Vec3 position = Vec3::Zero();
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Vec3 apply(const Vec3& x) const { return position + rotation * x; }
  RigidPose operator*(const RigidPose& b) const { return {apply(b.position), rotation * b.rotation}; }
  RigidPose inverse() const { return {-(rotation.transpose() * position), rotation.transpose()}; }
};

/// The rigid pose of an instrument's jaws (hinge and frame).
inline RigidPose jawsPose(const InstrumentPose& pose) { return {pose.hinge, pose.frame}; }

class Needle {
 public:
  struct Settings {
    std::string name;
    double radius = 8e-3;        // R (m)
    double arc = 2.356;          // α (rad): 3/8 of a circle
    double wire_radius = 2.5e-4; // r_w (m)
    RigidPose pose;              // the arc's centre and frame (u, v, w) at the start
    std::string thread;          // node path of the thread swaged to it ("": none)
    double abscissa = 0.0;       // the thread's end at the swage
    double stiffness = 2000.0;   // N/m, the swage's hold on the thread
  };
  /// One entry of "needles"; throws SceneError at the faulty field.
  static Settings settingsFromParams(const Params& p);

  explicit Needle(Settings settings);
  const Settings& settings() const { return settings_; }
  const std::string& name() const { return settings_.name; }

  /// The wire's axis at angle θ ∈ [0, α] for the pose `pose`.
  Vec3 point(const RigidPose& pose, double theta) const;
  Vec3 swage(const RigidPose& pose) const { return point(pose, 0.0); }
  Vec3 tip(const RigidPose& pose) const { return point(pose, settings_.arc); }

  const RigidPose& pose() const { return pose_; }
  /// Moves the needle to `now` at the step's start and `next` at its end (held by jaws), or keeps
  /// it still (next = now); the swage's hold on the thread follows.
  void move(const RigidPose& now, const RigidPose& next, double t, double h);

  /// The swage's hold on the thread (a ToolState the coupling force field reads).
  const std::shared_ptr<ToolState>& swageHold() const { return swage_hold_; }
  /// The swage clamps the thread's direction too: the thread leaves it along the needle's axis. A
  /// second hold, on the thread kSwageLead (m) of its length from its end, to the point that far
  /// behind the swage on the wire's tangent line there, X = P(0) − kSwageLead T(0) (T the unit
  /// tangent towards the tip); so the thread follows the needle's track through tissue.
  const std::shared_ptr<ToolState>& swageLeadHold() const { return swage_lead_hold_; }
  static constexpr double kSwageLead = 2e-3;
  /// X of the lead hold for the pose `pose`.
  Vec3 swageLead(const RigidPose& pose) const;

  /// Which instrument holds it (−1: none) and where, relative to that instrument's jaws.
  int holder = -1;
  RigidPose in_jaws;
  bool ever_held = false;

 private:
  Settings settings_;
  RigidPose pose_;
  std::shared_ptr<ToolState> swage_hold_ = std::make_shared<ToolState>();
  std::shared_ptr<ToolState> swage_lead_hold_ = std::make_shared<ToolState>();
};

}  // namespace filum::haptics
