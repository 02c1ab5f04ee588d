#include "filum/collision/register_components.hpp"

#include "filum/collision/capsule_obstacle.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/implicit_surface_obstacle.hpp"
#include "filum/collision/plane_obstacle.hpp"
#include "filum/collision/probe_sphere.hpp"
#include "filum/collision/sphere_collision_model.hpp"
#include "filum/collision/sphere_obstacle.hpp"
#include "filum/collision/vessel_lumen_obstacle.hpp"
#ifdef FILUM_WITH_CGAL
#include "filum/collision/triangle_mesh_obstacle.hpp"
#endif

namespace filum::collision {

void register_components(Factory& factory) {
  factory.add("SphereCollisionModel",
              "spheres at equal curvilinear spacing along the node's spline, resampled as it stretches (paper §3)",
              [](const Params& p) { return SphereCollisionModel::fromParams(p); });
  factory.add("ContactPipeline",
              "collision detection (grid broad phase, continuous) and penalty or unilateral contact response",
              [](const Params& p) { return ContactPipeline::fromParams(p); });
  factory.setDefault("CollisionPipeline", "ContactPipeline");

  factory.add("PlaneObstacle", "the half-space below a plane (table, inclined board)",
              [](const Params& p) { return PlaneObstacle::fromParams(p); });
  factory.add("SphereObstacle", "a fixed ball", [](const Params& p) { return SphereObstacle::fromParams(p); });
  factory.add("CapsuleObstacle", "the points within a radius of a segment (rod, shaft, vessel piece)",
              [](const Params& p) { return CapsuleObstacle::fromParams(p); });
  factory.add("ImplicitSurfaceObstacle", "a convolution surface f(x) = 0 around a skeleton polyline (Lenoir's vessels)",
              [](const Params& p) { return ImplicitSurfaceObstacle::fromParams(p); });
  factory.add("VesselLumenObstacle",
              "the wall of an artery tree from centrelines with radii, touched from inside (guidewires, catheters, coils)",
              [](const Params& p) { return VesselLumenObstacle::fromParams(p); });
  factory.add("ProbeSphere", "a sphere on a scripted trajectory that pushes threads (paper Fig. 1a probe)",
              [](const Params& p) { return ProbeSphere::fromParams(p); });
#ifdef FILUM_WITH_CGAL
  factory.add("TriangleMeshObstacle", "a triangle mesh (OFF/OBJ/STL/PLY): a closed organ, a cavity, a segmented vessel open at its ends (CGAL AABB tree)",
              [](const Params& p) { return TriangleMeshObstacle::fromParams(p); });
#else
  factory.addUnavailable("TriangleMeshObstacle", "FILUM_WITH_CGAL");
#endif
}

}  // namespace filum::collision
