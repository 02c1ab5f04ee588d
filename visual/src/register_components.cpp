#include "filum/visual/register_components.hpp"

#include "filum/visual/convolution_surface_model.hpp"
#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/mesh_model.hpp"
#include "filum/visual/obstacle_model.hpp"
#include "filum/visual/sphere_model.hpp"
#include "filum/visual/vessel_lumen_model.hpp"

namespace filum::visual {

void register_components(Factory& factory) {
  factory.add("GeneralizedCylinder",
              "visual skin of a spline: tube with rotation-minimizing frames, radius profile, end caps",
              [](const Params& p) { return GeneralizedCylinderModel::fromParams(p); });
  factory.add("SphereModel", "visual spheres: fixed, on a spline, evenly along it, or at a constraint's target",
              [](const Params& p) { return SphereModel::fromParams(p); });
  factory.add("ObstacleModel",
              "an obstacle drawn as it is (plane patch, sphere, capsule, mesh), in the colour given; "
              "obstacles nothing names are drawn in default colours",
              [](const Params& p) { return ObstacleModel::fromParams(p); });
  factory.add("MeshModel", "rigid visual mesh from an .obj, .off or .ply file (organs, vessels)",
              [](const Params& p) { return MeshModel::fromParams(p); });
  if (convolutionSurfaceMeshingAvailable())
    factory.add("ConvolutionSurfaceModel",
                "convolution (skeleton) implicit surface around a spline, meshed for display by CGAL",
                [](const Params& p) { return ConvolutionSurfaceModel::fromParams(p); });
  else
    factory.addUnavailable("ConvolutionSurfaceModel", "FILUM_WITH_CGAL");
  if (convolutionSurfaceMeshingAvailable())
    factory.add("VesselLumenModel", "the wall of a vessel tree (centrelines with radii), translucent, meshed by CGAL",
                [](const Params& p) { return VesselLumenModel::fromParams(p); });
  else
    factory.addUnavailable("VesselLumenModel", "FILUM_WITH_CGAL");
}

}  // namespace filum::visual
