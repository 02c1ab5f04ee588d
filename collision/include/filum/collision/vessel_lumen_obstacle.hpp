// VesselLumenObstacle: the wall of an artery tree, touched from inside — what a guidewire, a
// catheter or a coil stays in. The lumen is a geometry::VesselTree (centrelines with radii,
// branches joined smoothly, open inlet and outlets), queried as its field: the wall's signed
// distance φ(x) / |∇φ(x)| (positive inside the lumen, where the instruments are free) and the
// normal n = ∇φ / |∇φ|, pointing from the wall into the lumen ([Lenoir talk 2008], catheter navigation:
// "collision detection achieved by evaluating f(x), collision response along f(x)").
//
// Scene: "file": the tree's JSON file (relative to the scene file; format in vessel_tree.hpp and
// docs/vessels.md) or the tree inline ("units", "blend", "branches"); "friction": μ.
// Units are checked: a lumen whose largest radius is above 5 cm (wider than any human artery, the
// aortic root is about 1.5 cm) or below 0.1 mm (narrower than any vessel an instrument enters) is
// refused, naming the units it probably needs.
#pragma once

#include <memory>

#include "filum/collision/obstacle.hpp"
#include "filum/geometry/vessel_tree.hpp"

namespace filum::collision {

class VesselLumenObstacle final : public Obstacle {
 public:
  static constexpr double kLargestRadius = 0.05;   // m: no human artery is wider
  static constexpr double kSmallestRadius = 1e-4;  // m: no vessel an instrument enters is narrower

  explicit VesselLumenObstacle(std::shared_ptr<const geometry::VesselTree> tree);
  static std::unique_ptr<VesselLumenObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "VesselLumenObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;

  const geometry::VesselTree& tree() const { return *tree_; }
  std::shared_ptr<const geometry::VesselTree> sharedTree() const { return tree_; }

 private:
  std::shared_ptr<const geometry::VesselTree> tree_;
};

/// The vessel tree a lumen component's parameters describe: "file" (relative to the scene file) or
/// inline "units"/"blend"/"branches"; the radius check above. Shared by the obstacle, the lumen's
/// picture and the navigation metrics. Throws SceneError naming the place.
std::shared_ptr<const geometry::VesselTree> readVesselTree(const Params& p);

}  // namespace filum::collision
