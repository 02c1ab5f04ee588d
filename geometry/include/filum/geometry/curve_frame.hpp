// An orthonormal frame attached to a point of a curve: the unit tangent T and two unit normals
// N, B with B = T × N (right-handed). Produced by the rotation-minimizing frames
// (rotation_minimizing_frames.hpp) and the Frenet frame (frenet_frame.hpp); used to skin
// generalized cylinders and to orient tools along a thread.
#pragma once

#include <Eigen/Geometry>  // cross products

#include "filum/core/types.hpp"

namespace filum::geometry {

struct CurveFrame {
  Vec3 origin = Vec3::Zero();     // P(s)
  Vec3 tangent = Vec3::UnitX();   // T, unit
  Vec3 normal = Vec3::UnitY();    // N, unit, ⊥ T
  Vec3 binormal = Vec3::UnitZ();  // B = T × N
};

}  // namespace filum::geometry
