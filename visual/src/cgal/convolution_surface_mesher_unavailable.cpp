// Built instead of convolution_surface_mesher.cpp when FILUM_WITH_CGAL is OFF.
#include <stdexcept>

#include "filum/visual/convolution_surface_mesher.hpp"

namespace filum::visual {

bool convolutionSurfaceMeshingAvailable() { return false; }

TriangleMesh meshImplicitSurface(const ImplicitFunction&, const ImplicitGradient&, const Vec3&, double,
                                 const SurfaceMeshingCriteria&) {
  throw std::runtime_error("meshing implicit surfaces needs CGAL, which this build left out: reconfigure with "
                           "-DFILUM_WITH_CGAL=ON (Debian package libcgal-dev)");
}

TriangleMesh meshConvolutionSurface(const geometry::ConvolutionSurface&, const Vec3&, double,
                                    const SurfaceMeshingCriteria&) {
  throw std::runtime_error("meshing implicit surfaces needs CGAL, which this build left out: reconfigure with "
                           "-DFILUM_WITH_CGAL=ON (Debian package libcgal-dev)");
}

}  // namespace filum::visual
