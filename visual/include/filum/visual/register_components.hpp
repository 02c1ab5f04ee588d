// The visual library's scene components (visual_model.hpp): GeneralizedCylinder, SphereModel,
// MeshModel and ConvolutionSurfaceModel (the last needs CGAL, CMake option FILUM_WITH_CGAL).
#pragma once

#include "filum/core/factory.hpp"

namespace filum::visual {

void register_components(Factory& factory);

}  // namespace filum::visual
