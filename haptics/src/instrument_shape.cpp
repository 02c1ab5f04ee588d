#include "filum/haptics/instrument_shape.hpp"

#include <cmath>

namespace filum::haptics {

Eigen::Matrix3d instrumentFrame(const Vec3& direction, double roll) {
  const Vec3 d = direction.normalized();
  // cos 25° = 0.906: nearer to ±z, the projection of +z on d's normal plane is too short to trust.
  const Vec3 up = std::abs(d.z()) < 0.906 ? Vec3::UnitZ() : Vec3::UnitX();
  const Vec3 n0 = (up - up.dot(d) * d).normalized();
  const Vec3 n = Eigen::AngleAxisd(roll, d) * n0;
  Eigen::Matrix3d frame;
  frame.col(0) = d;
  frame.col(1) = n;
  frame.col(2) = d.cross(n);
  return frame;
}

Capsule InstrumentShape::shaft(const InstrumentPose& pose) const {
  return {pose.hinge - shaft_length * pose.axis(), pose.hinge, shaft_radius};
}

Capsule InstrumentShape::jaw(const InstrumentPose& pose, double opening, int side) const {
  const double phi = halfAngle(opening);
  const Vec3 direction = std::cos(phi) * pose.axis() + side * std::sin(phi) * pose.opening();
  return {pose.hinge, pose.hinge + jaw_length * direction, jaw_radius};
}

Vec3 InstrumentShape::tip(const InstrumentPose& pose, double opening) const {
  return pose.hinge + jaw_length * std::cos(halfAngle(opening)) * pose.axis();
}

double betweenJaws(const InstrumentShape& shape, const InstrumentPose& pose, double opening, const Vec3& x, double r) {
  const JawCoordinates c = jawCoordinates(pose, x);
  const double phi = shape.halfAngle(opening);
  if (c.along < 0.0 || c.along > shape.jaw_length * std::cos(phi)) return -1.0;
  if (std::abs(c.across) > shape.jaw_radius + r) return -1.0;
  if (std::abs(c.lateral) > c.along * std::tan(phi) + shape.jaw_radius + r) return -1.0;
  return std::hypot(c.lateral, c.across);
}

}  // namespace filum::haptics
