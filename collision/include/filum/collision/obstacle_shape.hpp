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
    kMesh,     // the closed triangle mesh `mesh` (world coordinates); `cavity`: bodies stay inside
  };
  Kind kind = Kind::kNone;
  Vec3 a = Vec3::Zero();
  Vec3 b = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
  double radius = 0.0;
  const TriangleMeshSurface* mesh = nullptr;
  bool cavity = false;
};

}  // namespace filum::collision
