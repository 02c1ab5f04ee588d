// Meshing of a convolution surface (geometry/convolution_surface.hpp), {x : f(x) = T − F(x) = 0},
// for display, with CGAL's surface mesher (J.-D. Boissonnat, S. Oudot, "Provably good sampling
// and meshing of surfaces", Graphical Models 67, 2005; CGAL package Surface_mesher:
// make_surface_mesh on an Implicit_surface_3, manifold output). The facets satisfy the criteria
// below (restricted Delaunay refinement); normals are the exact field normals −∇F/|∇F|, and each
// triangle is oriented to agree with them (counter-clockwise seen from outside).
//
// CGAL stays in one translation unit (src/cgal/convolution_surface_mesher.cpp), compiled only
// with the CMake option FILUM_WITH_CGAL; without it meshing throws, naming the option.
// The same mesher serves any implicit surface given as a function (meshImplicitSurface): the lumen
// of a vessel tree (vessel_lumen_model.hpp) is meshed this way.
#pragma once

#include <functional>

#include "filum/geometry/convolution_surface.hpp"
#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

struct SurfaceMeshingCriteria {
  double angle_degrees = 30.0;  // lower bound on the facets' smallest angle (<= 30 guarantees termination)
  double facet_size = 1e-3;     // upper bound on the facets' Delaunay-ball radius (m)
  double approximation = 1e-4;  // upper bound on the distance facet centre – surface (m)
};

/// True if this build meshes implicit surfaces (FILUM_WITH_CGAL=ON).
bool convolutionSurfaceMeshingAvailable();

/// Meshes the component of the surface around `inside` (a point with f < 0, e.g. on the
/// skeleton) contained in the ball (inside, bounding_radius). Throws std::invalid_argument if
/// `inside` is not inside, std::runtime_error without CGAL or if nothing was meshed.
/// An implicit surface {f = 0}, f < 0 inside, with its outward gradient for the normals: the
/// component around `inside` within the ball (inside, bounding_radius), which must contain it.
/// Throws as meshConvolutionSurface.
using ImplicitFunction = std::function<double(const Vec3&)>;
using ImplicitGradient = std::function<Vec3(const Vec3&)>;
TriangleMesh meshImplicitSurface(const ImplicitFunction& f, const ImplicitGradient& gradient, const Vec3& inside,
                                 double bounding_radius, const SurfaceMeshingCriteria& criteria);

TriangleMesh meshConvolutionSurface(const geometry::ConvolutionSurface& surface, const Vec3& inside,
                                    double bounding_radius, const SurfaceMeshingCriteria& criteria);

}  // namespace filum::visual
