// ImplicitSurfaceObstacle: a convolution surface f(x) = T − F(x) = 0 around a skeleton polyline
// (geometry::ConvolutionSurface; [Lenoir talk 2008], catheter navigation: "convolution surface for contact
// f(x) = 0 ... collision detection achieved by evaluating f(x), collision response along f(x)").
// Inside where f < 0. The distance to the surface is estimated to first order by the Newton
// step of f along its gradient,
//   d(x) ≈ f(x) / |∇f(x)|,   n = ∇f / |∇f| = −∇F / |∇F|,   closest point x − d n,
// exact on the surface and accurate to O(d² κ) near it (κ: curvature of the level sets), which
// is where contacts are resolved.
#pragma once

#include <memory>

#include <Eigen/Geometry>

#include "filum/collision/obstacle.hpp"
#include "filum/geometry/convolution_surface.hpp"

namespace filum::collision {

class ImplicitSurfaceObstacle final : public Obstacle {
 public:
  /// skeleton: m >= 2 points (m), radius R > 0 of the tube (m), sharpness s >= 0 (1/m, 0: 1/R).
  ImplicitSurfaceObstacle(const Points& skeleton, double radius, double sharpness);
  /// "skeleton": [[x, y, z], ...] (a polyline), "radius": R (m), "sharpness": s (1/m, default
  /// 1/R), "friction": μ.
  static std::unique_ptr<ImplicitSurfaceObstacle> fromParams(const Params& p);

  std::string typeName() const override { return "ImplicitSurfaceObstacle"; }
  bool sample(const Vec3& x, double max_distance, SurfaceSample& out) const override;

  const geometry::ConvolutionSurface& surface() const { return surface_; }

 private:
  geometry::ConvolutionSurface surface_;
  Eigen::AlignedBox3d skeleton_box_;
};

}  // namespace filum::collision
