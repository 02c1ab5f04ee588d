#include "filum/collision/triangle_mesh_obstacle.hpp"

#include <filesystem>

#include <Eigen/Geometry>

#include "filum/geometry/mesh_units.hpp"

namespace filum::collision {

TriangleMeshObstacle::TriangleMeshObstacle(std::shared_ptr<const TriangleMeshSurface> surface, bool cavity)
    : surface_(std::move(surface)), cavity_(cavity) {}

std::unique_ptr<TriangleMeshObstacle> TriangleMeshObstacle::fromParams(const Params& p) {
  const std::string file = p.string("file");
  const double scale = geometry::meshScale(p);  // "units" × "scale": metres per unit of the file
  const Vec3 translation = p.vec3("translation", Vec3::Zero());
  const std::string side = p.string("side", "outside");
  if (side != "outside" && side != "inside")
    p.fail("side", "\"outside\" (a solid the bodies stay out of) or \"inside\" (a cavity they stay in)",
           "\"" + side + "\"");
  // Relative paths are relative to the scene file's folder.
  std::filesystem::path path(file);
  if (path.is_relative() && !p.file().empty()) path = std::filesystem::path(p.file()).parent_path() / path;
  std::shared_ptr<const TriangleMeshSurface> surface;
  try {
    surface = TriangleMeshSurface::read(path.string(), scale, translation);
  } catch (const std::exception& e) {
    p.fail("file", "a closed triangle mesh file (.off, .obj, .stl, .ply)", "\"" + file + "\" (" + e.what() + ")");
  }
  if (side == "inside") {
    // The cavity's side test trusts the faces' winding (counter-clockwise seen from outside):
    // a mesh wound the other way encloses a negative volume, Σ a·(b × c)/6.
    double volume = 0.0;
    for (const auto& t : surface->triangles()) {
      const Vec3 a = surface->vertices().row(t[0]).transpose(), b = surface->vertices().row(t[1]).transpose(),
                 c = surface->vertices().row(t[2]).transpose();
      volume += a.dot(b.cross(c)) / 6.0;
    }
    if (!(volume > 0.0))
      p.fail("file", "a closed mesh wound counter-clockwise seen from outside (a positive enclosed volume) for \"side\": \"inside\"",
             "\"" + file + "\" (enclosed volume " + std::to_string(volume) + " m³: wound inward)");
  }
  auto obstacle = std::make_unique<TriangleMeshObstacle>(std::move(surface), side == "inside");
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

}  // namespace filum::collision
