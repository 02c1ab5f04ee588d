// VesselLumenModel (scene type "VesselLumenModel"): the wall of a vessel tree drawn as a
// translucent shaded surface — the lumen the instruments move in (collision/vessel_lumen_
// obstacle.hpp takes the same parameters). The tree's field (geometry/vessel_tree.hpp), with its
// open ends cut flat, is meshed by CGAL's surface mesher (convolution_surface_mesher.hpp:
// meshImplicitSurface; normals are the field's) once, the first time its mesh is asked for — when
// pictures or meshes are made, not when the scene is loaded, checked or stepped: meshing the aortic
// arch takes seconds, which a run without pictures, `filum check` or a test should not pay.
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
  /// The tree's wall, meshed at the first update with this facet size and approximation (m).
  VesselLumenModel(std::shared_ptr<const geometry::VesselTree> tree, double facet_size, double approximation)
      : tree_(std::move(tree)), facet_size_(facet_size), approximation_(approximation) {}
  static std::unique_ptr<VesselLumenModel> fromParams(const Params& p);

  /// The tree's wall with its open ends cut flat, meshed (facet size and approximation in metres).
  static TriangleMesh meshWall(const geometry::VesselTree& tree, double facet_size, double approximation);

  std::string typeName() const override { return "VesselLumenModel"; }
  /// X-ray: a vessel filled with contrast: faint, darker where two walls overlap.
  double defaultXrayOpacity() const override { return 0.2; }
  bool needsBody() const override { return false; }
  void update(const SceneState&) override {}
  /// The wall, meshed the first time it is asked for (throws std::runtime_error if CGAL cannot).
  const TriangleMesh& mesh(int = 0) const override;

 private:
  std::shared_ptr<const geometry::VesselTree> tree_;
  double facet_size_ = 0.0, approximation_ = 0.0;
  // Meshed on demand by the drawing thread (the visual side is single-threaded).
  mutable bool meshed_ = false;
  mutable TriangleMesh mesh_;
};

}  // namespace filum::visual
