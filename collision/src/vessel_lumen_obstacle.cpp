#include "filum/collision/vessel_lumen_obstacle.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "filum/core/scene_error.hpp"

namespace filum::collision {

std::shared_ptr<const geometry::VesselTree> readVesselTree(const Params& p) {
  std::shared_ptr<geometry::VesselTree> tree;
  if (p.has("file")) {
    const std::string file = p.string("file");
    std::filesystem::path path(file);  // relative to the scene file's folder
    if (path.is_relative() && !p.file().empty()) path = std::filesystem::path(p.file()).parent_path() / path;
    if (!std::filesystem::is_regular_file(path))
      p.fail("file", "a vessel tree file (JSON: units, blend, branches)", "\"" + file + "\" (no such file)");
    try {
      tree = std::make_shared<geometry::VesselTree>(geometry::VesselTree::read(path.string()));
    } catch (const SceneError&) {
      throw;
    } catch (const std::exception& e) {
      p.fail("file", "a valid vessel tree", "\"" + file + "\" (" + e.what() + ")");
    }
  } else {
    if (!p.has("branches")) p.fail("file", "a vessel tree: \"file\", or \"branches\" inline");
    try {
      tree = std::make_shared<geometry::VesselTree>(geometry::VesselTree::fromParams(p));
    } catch (const SceneError&) {
      throw;
    } catch (const std::exception& e) {
      p.fail("branches", "a valid vessel tree", e.what());
    }
  }
  const double r = tree->maxRadius();
  auto describe = [&](double metres) {
    std::ostringstream s;
    s << metres << " m";
    return s.str();
  };
  const std::string key = p.has("file") ? "file" : "branches";
  if (r > VesselLumenObstacle::kLargestRadius)
    p.fail(key, "a lumen of human size (largest radius at most 5 cm; the aortic root is about 1.5 cm)",
           "a largest radius of " + describe(r) + " (a file in mm read as metres? set \"units\": \"mm\")");
  if (r < VesselLumenObstacle::kSmallestRadius)
    p.fail(key, "a lumen an instrument can enter (largest radius at least 0.1 mm)",
           "a largest radius of " + describe(r) + " (a file in metres read as mm? set \"units\": \"m\")");
  return tree;
}

VesselLumenObstacle::VesselLumenObstacle(std::shared_ptr<const geometry::VesselTree> tree) : tree_(std::move(tree)) {}

std::unique_ptr<VesselLumenObstacle> VesselLumenObstacle::fromParams(const Params& p) {
  auto obstacle = std::make_unique<VesselLumenObstacle>(readVesselTree(p));
  obstacle->readCommon(p);
  return obstacle;
}

bool VesselLumenObstacle::sample(const Vec3& x, double max_distance, SurfaceSample& out) const {
  // The field is exact down to a radius outside the wall: a point that went farther through it
  // still gets pushed back; beyond that (no branch near) there is nothing to push against.
  const geometry::VesselTree::Sample s = tree_->sample(x, std::max(max_distance, tree_->maxRadius()));
  if (s.branch < 0) return false;
  const double g = s.gradient.norm();
  if (!(g > 0.0)) return false;  // on a centreline: the wall is a radius away in every direction
  const double d = s.value / g;  // φ / |∇φ|: the distance to the wall to first order
  if (d > max_distance) return false;
  out.distance = d;
  out.normal = s.gradient / g;  // from the wall into the lumen
  out.point = x - d * out.normal;
  out.velocity.setZero();
  return true;
}

}  // namespace filum::collision
