// InstrumentShape: the rigid geometry of a surgical instrument — a shaft ending at the jaws'
// hinge and two jaws (grasper, bipolar forceps) or blades (scissors) that open symmetrically
// about the shaft's axis — and where its parts are for a pose and a jaw opening. Every part is a
// capsule (a segment with a radius): what the threads collide with, what is drawn, and what the
// jaws' tests ("is a thread between them?") measure against.
//
// Pose: the hinge H (m) and a right-handed frame (d, n, b): d along the shaft towards the tip,
// n the direction in which the jaws open, b = d × n. With the opening o ∈ [0, 1] each jaw turns
// by φ = o · max_angle / 2 about b, so the jaws' axes are
//   jaw k (k = ±1): from H along d_k = cos φ d + k sin φ n, length L_jaw;
// the shaft runs from H − L_shaft d to H. The tip is the midpoint of the jaws' ends.
#pragma once

#include <cmath>

#include <Eigen/Geometry>

#include "filum/core/types.hpp"

namespace filum::haptics {

/// A segment with a radius: the points within `radius` of [a, b].
struct Capsule {
  Vec3 a = Vec3::Zero(), b = Vec3::Zero();
  double radius = 0.0;
};

struct InstrumentPose {
  Vec3 hinge = Vec3::Zero();
  Eigen::Matrix3d frame = Eigen::Matrix3d::Identity();  // columns d, n, b
  Vec3 axis() const { return frame.col(0); }
  Vec3 opening() const { return frame.col(1); }
};

/// The frame (d, n, b) of a shaft pointing along `direction`, rolled by `roll` (rad) about it:
/// at roll 0, n is the unit vector normal to d nearest to the world's +z (to +x when d is within
/// 25° of ±z), so jaws of a shaft held level open up and down.
Eigen::Matrix3d instrumentFrame(const Vec3& direction, double roll);

struct InstrumentShape {
  double shaft_length = 0.10;  // m (drawn and colliding; a laparoscopic shaft is 0.33 m)
  double shaft_radius = 2.5e-3;  // m (a 5 mm instrument)
  double jaw_length = 0.018;   // m
  double jaw_radius = 1.0e-3;  // m
  double max_angle = 0.9;      // rad between the jaws fully open (o = 1)

  /// Half the angle between the jaws at opening o ∈ [0, 1].
  double halfAngle(double opening) const { return 0.5 * max_angle * opening; }
  Capsule shaft(const InstrumentPose& pose) const;
  /// Jaw k = +1 or −1 at opening o.
  Capsule jaw(const InstrumentPose& pose, double opening, int side) const;
  /// The midpoint of the jaws' ends.
  Vec3 tip(const InstrumentPose& pose, double opening) const;
};

/// Where a point x lies relative to the jaws: `along` its distance from the hinge along d,
/// `across` its distance from the jaws' plane (along b), `lateral` along n.
struct JawCoordinates {
  double along = 0.0, lateral = 0.0, across = 0.0;
};
inline JawCoordinates jawCoordinates(const InstrumentPose& pose, const Vec3& x) {
  const Vec3 r = pose.frame.transpose() * (x - pose.hinge);
  return {r.x(), r.y(), r.z()};
}

/// Whether a thread of radius r with its axis at x lies between the jaws at opening o: within the
/// jaws' length, no farther than the jaws' radius from their plane, and inside the wedge they span
/// (its half-width at `along` is along · tan φ, plus the jaws' and the thread's radii). Returns
/// the distance from the jaws' midline (m) when it does, a negative number when it does not.
double betweenJaws(const InstrumentShape& shape, const InstrumentPose& pose, double opening, const Vec3& x, double r);

/// Whether jaws at opening o have closed onto a thread of radius r at `along` from the hinge:
/// the gap between their surfaces there, 2 (along · sin φ − r_jaw), is at most its diameter.
inline bool jawsClosedOn(const InstrumentShape& shape, double opening, double along, double r) {
  return along * std::sin(shape.halfAngle(opening)) - shape.jaw_radius <= r;
}

}  // namespace filum::haptics
