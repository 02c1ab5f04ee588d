#include "filum/visual/vessel_lumen_model.hpp"

#include <algorithm>
#include <limits>

#include "filum/collision/vessel_lumen_obstacle.hpp"

namespace filum::visual {

TriangleMesh VesselLumenModel::meshWall(const geometry::VesselTree& tree, double facet_size, double approximation) {
  // f = −φ (negative inside the lumen), open ends capped; outward gradient −∇φ.
  const double reach = tree.maxRadius();
  auto f = [&](const Vec3& x) { return -tree.sample(x, reach, true).value; };
  auto gradient = [&](const Vec3& x) { return Vec3(-tree.sample(x, reach, true).gradient); };
  // A point strictly inside: the middle of the first branch's first segment.
  const geometry::VesselTree::Branch& first = tree.branch(0);
  const Vec3 inside = 0.5 * (first.points.row(0) + first.points.row(1)).transpose();
  // The ball CGAL meshes in must hold the whole surface: the box of the centres grown by the
  // radii, and a margin.
  const double bounding_radius = 0.5 * tree.bounds().diagonal().norm() + tree.maxRadius() +
                                 (inside - tree.bounds().center()).norm();
  SurfaceMeshingCriteria criteria;
  criteria.facet_size = facet_size;
  criteria.approximation = approximation;
  return meshImplicitSurface(f, gradient, inside, bounding_radius, criteria);
}

const TriangleMesh& VesselLumenModel::mesh(int) const {
  if (!meshed_) {
    mesh_ = meshWall(*tree_, facet_size_, approximation_);
    meshed_ = true;
  }
  return mesh_;
}

std::unique_ptr<VesselLumenModel> VesselLumenModel::fromParams(const Params& p) {
  const auto tree = collision::readVesselTree(p);
  double smallest = std::numeric_limits<double>::infinity();
  for (int b = 0; b < tree->branchCount(); ++b) smallest = std::min(smallest, tree->branch(b).radii.minCoeff());
  const double facet = p.positive({"facet_size", "m"}, 0.5 * smallest);
  const double approximation = p.positive({"approximation", "m"}, 0.1 * facet);
  auto model = std::make_unique<VesselLumenModel>(tree, facet, approximation);
  model->setMaterial(Material::fromParams(p, Material{Vec3(0.8, 0.25, 0.25), 0.35}));
  return model;
}

}  // namespace filum::visual
