#include "filum/collision/triangle_mesh_obstacle.hpp"

#include <cmath>
#include <filesystem>
#include <limits>

#include <Eigen/Geometry>

#include "filum/geometry/mesh_units.hpp"

namespace filum::collision {

TriangleMeshObstacle::TriangleMeshObstacle(std::shared_ptr<const TriangleMeshSurface> surface, bool cavity)
    : surface_(std::move(surface)), cavity_(cavity) {}

std::unique_ptr<TriangleMeshObstacle> TriangleMeshObstacle::fromParams(const Params& p) {
  const std::string file = p.string("file");
  const double scale = geometry::meshScale(p);  // "units" × "scale": metres per unit of the file
  const Vec3 translation = p.vec3({"translation", "m"}, Vec3::Zero());
  const std::string side = p.string("side", "outside");
  if (side != "outside" && side != "inside")
    p.fail("side", "\"outside\" (a solid the bodies stay out of) or \"inside\" (a cavity they stay in)",
           "\"" + side + "\"");
  // Relative paths are relative to the scene file's folder.
  std::filesystem::path path(file);
  if (path.is_relative() && !p.file().empty()) path = std::filesystem::path(p.file()).parent_path() / path;
  const bool cavity = side == "inside";
  std::shared_ptr<const TriangleMeshSurface> surface;
  try {
    surface = TriangleMeshSurface::read(path.string(), scale, translation, /*allow_open=*/cavity);
  } catch (const std::exception& e) {
    p.fail("file",
           cavity ? "a triangle mesh file (.off, .obj, .stl, .ply), closed or open at its ends"
                  : "a closed triangle mesh file (.off, .obj, .stl, .ply) (an open one only as \"side\": \"inside\")",
           "\"" + file + "\" (" + e.what() + ")");
  }
  if (cavity) {
    // The side tests trust the faces' winding (counter-clockwise seen from outside the cavity).
    // Which way a file is wound is found from the volume it encloses with its holes (a vessel's
    // inlet and outlets) closed: negative, the faces are wound inwards and are turned round;
    // zero to round-off (ε Σ|a·(b × c)|/6, with a margin of 1e3 for the sum's length), the mesh
    // encloses nothing (a sheet, a surface folded onto itself) and has no inner side to find.
    double scale_of_terms = 0.0;
    const double volume = surface->enclosedVolume(scale_of_terms);
    if (std::abs(volume) <= 1e3 * std::numeric_limits<double>::epsilon() * scale_of_terms)
      p.fail("file", "a mesh that encloses a volume (its holes closed) for \"side\": \"inside\", so that its inner side can be found",
             "\"" + file + "\" (enclosed volume " + std::to_string(volume) + " m³)");
    if (volume < 0.0) surface = surface->reversed();
  }
  auto obstacle = std::make_unique<TriangleMeshObstacle>(std::move(surface), cavity);
  obstacle->readCommon(p);
  return obstacle;
}

bool TriangleMeshObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  if (cavity_) return sampleCavity(x, max_distance, out);
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

bool TriangleMeshObstacle::sampleCavity(const Vec3& x, double max_distance, SurfaceSample& out) const {
  if (!surface_->closed()) return sampleLumen(x, max_distance, out);
  Vec3 face_normal;
  const Vec3 c = surface_->closestPoint(x, face_normal);
  const Vec3 away = x - c;
  const double u = away.norm();
  // Inside the closed surface (the free side): the sign of (x − c)·n_f when clearly off the
  // face's plane, else the exact test.
  const double along = away.dot(face_normal);
  const bool inside = std::abs(along) > 0.5 * u ? along < 0.0 : surface_->inside(x);
  if (inside && u > max_distance) return false;
  // d = +u inside (clear of the wall), −u outside (through it); n into the cavity.
  out.distance = inside ? u : -u;
  out.point = c;
  out.normal = u > 1e-12 * (1.0 + surface_->bounds().diagonal().norm()) ? Vec3((inside ? away : -away) / u)
                                                                         : Vec3(-face_normal);
  out.velocity.setZero();
  return true;
}

bool TriangleMeshObstacle::sampleLumen(const Vec3& x, double max_distance, SurfaceSample& out) const {
  // An open mesh: the side of x from the pseudo-normal of the closest feature (exact wherever the
  // wall is closed around c). Farther than max_distance from the wall, on either side, x is free:
  // inside, clear of the wall; outside, an instrument outside the vessel on its way to the
  // introducer (a body in the lumen is held by contact before it gets that far through the wall).
  // Where c is on the rim of an opening, the wall is a thin edge with free space on both sides: x
  // is that far from it, d = +|x − c|, and pushed away from the rim — into the lumen from inside,
  // away from the vessel from outside, never through the wall.
  const TriangleMeshSurface::ClosestFeature c = surface_->closestFeature(x);
  const Vec3 away = x - c.point;
  const double u = away.norm();
  if (u > max_distance) return false;
  const bool has_direction = u > 1e-12 * (1.0 + surface_->bounds().diagonal().norm());
  const bool inside = c.on_border || away.dot(c.normal) < 0.0;
  out.distance = inside ? u : -u;
  out.point = c.point;
  out.normal = has_direction ? Vec3((inside ? away : -away) / u) : Vec3(-c.normal);
  out.velocity.setZero();
  return true;
}

}  // namespace filum::collision
