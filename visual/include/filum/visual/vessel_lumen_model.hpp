// VesselLumenModel (scene type "VesselLumenModel"): the wall of a vessel tree drawn as a
// translucent shaded surface — the lumen the instruments move in (collision/vessel_lumen_
// obstacle.hpp takes the same parameters). The tree's field (geometry/vessel_tree.hpp), with its
// open ends cut flat, is meshed once at load by CGAL's surface mesher (convolution_surface_
// mesher.hpp: meshImplicitSurface); normals are the field's.
//
// Scene parameters: "file" (the tree's JSON, relative to the scene file) or the tree inline
// ("units", "blend", "branches"); "facet_size" (m, default half the smallest radius),
// "approximation" (m, default a tenth of the facet size), "color" (default a vessel red), "opacity"
// (default 0.35). Needs CGAL (CMake option FILUM_WITH_CGAL).
#pragma once

#include <memory>

#include "filum/geometry/vessel_tree.hpp"
#include "filum/visual/convolution_surface_mesher.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class VesselLumenModel final : public VisualModel {
 public:
  explicit VesselLumenModel(TriangleMesh mesh) : mesh_(std::move(mesh)) {}
  static std::unique_ptr<VesselLumenModel> fromParams(const Params& p);

  /// The tree's wall with its open ends cut flat, meshed (facet size and approximation in metres).
  static TriangleMesh meshWall(const geometry::VesselTree& tree, double facet_size, double approximation);

  std::string typeName() const override { return "VesselLumenModel"; }
  bool needsBody() const override { return false; }
  void update(const SceneState&) override {}
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

 private:
  TriangleMesh mesh_;
};

}  // namespace filum::visual
