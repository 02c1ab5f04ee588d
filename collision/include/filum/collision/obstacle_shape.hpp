// ObstacleShape: what an obstacle looks like, for the visual side — the primitive and its
// parameters at the obstacle's current time (after its last moveTo). The visual side draws any
// obstacle through this description (visual/obstacle_model.hpp), never by casting to its type.
#pragma once

#include "filum/core/types.hpp"

namespace filum::collision {

class TriangleMeshSurface;

struct ObstacleShape {
  enum class Kind {
    kNone,     // nothing to draw here (drawn by its own model: an instrument, an implicit surface)
    kPlane,    // the plane through `a` with outward unit normal `normal` (unbounded)
    kSphere,   // centre `a`, `radius`
    kCapsule,  // the points within `radius` of the segment [a, b]
    kMesh,     // the triangle mesh `mesh` (world coordinates; open only as a cavity); `cavity`: bodies stay inside
  };
  Kind kind = Kind::kNone;
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double radius = 0.0;
  const TriangleMeshSurface* mesh = nullptr;
  bool cavity = false;

  static ObstacleShape plane(const Vec3& point, const Vec3& normal) {
    return {Kind::kPlane, point, Vec3::Zero(), normal, 0.0, nullptr, false};
  }
  static ObstacleShape sphere(const Vec3& center, double radius) {
    return {Kind::kSphere, center, Vec3::Zero(), Vec3::UnitZ(), radius, nullptr, false};
  }
  static ObstacleShape capsule(const Vec3& a, const Vec3& b, double radius) {
    return {Kind::kCapsule, a, b, Vec3::UnitZ(), radius, nullptr, false};
  }
  static ObstacleShape triangleMesh(const TriangleMeshSurface& surface, bool cavity) {
    return {Kind::kMesh, Vec3::Zero(), Vec3::Zero(), Vec3::UnitZ(), 0.0, &surface, cavity};
  }
};

}  // namespace filum::collision
