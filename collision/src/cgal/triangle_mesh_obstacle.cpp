#include "filum/collision/triangle_mesh_obstacle.hpp"

#include <filesystem>

#include <Eigen/Geometry>

#include "filum/geometry/mesh_units.hpp"

namespace filum::collision {

TriangleMeshObstacle::TriangleMeshObstacle(std::shared_ptr<const TriangleMeshSurface> surface)
    : surface_(std::move(surface)) {}

std::unique_ptr<TriangleMeshObstacle> TriangleMeshObstacle::fromParams(const Params& p) {
  const std::string file = p.string("file");
  const double scale = geometry::meshScale(p);  // "units" × "scale": metres per unit of the file
  const Vec3 translation = p.vec3("translation", Vec3::Zero());
  // Relative paths are relative to the scene file's folder.
  std::filesystem::path path(file);
  if (path.is_relative() && !p.file().empty()) path = std::filesystem::path(p.file()).parent_path() / path;
  std::shared_ptr<const TriangleMeshSurface> surface;
  try {
    surface = TriangleMeshSurface::read(path.string(), scale, translation);
  } catch (const std::exception& e) {
    p.fail("file", "a closed triangle mesh file (.off, .obj, .stl, .ply)", "\"" + file + "\" (" + e.what() + ")");
  }
  auto obstacle = std::make_unique<TriangleMeshObstacle>(std::move(surface));
  obstacle->readCommon(p);
  return obstacle;
}

bool TriangleMeshObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  // Early out on the bounding box: farther than max_distance from it, no contact possible.
  if (surface_->bounds().exteriorDistance(x) > max_distance) return false;
  const Vec3 c = surface_->closestPoint(x);
  const double unsigned_distance = (x - c).norm();
  if (unsigned_distance > max_distance && !surface_->bounds().contains(x)) return false;
  const bool inside = surface_->inside(x);
  if (!inside && unsigned_distance > max_distance) return false;
  // d = ±|x − c|, n along x − c (outside) or c − x (inside); on the surface, the face normal.
  out.distance = inside ? -unsigned_distance : unsigned_distance;
  out.point = c;
  out.normal = unsigned_distance > 1e-12 * (1.0 + surface_->bounds().diagonal().norm())
                   ? Vec3((inside ? c - x : x - c) / unsigned_distance)
                   : surface_->nearestFaceNormal(x);
  out.velocity.setZero();
  return true;
}

}  // namespace filum::collision
