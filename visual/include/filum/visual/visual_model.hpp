// VisualModel: the visual side of the three-sided model (docs/architecture.md, "The three-sided
// model"): what is drawn or exported for a body — a skinned tube, spheres, a mesh from a file, a
// meshed implicit surface. It reads the body's DOFs through a mapping (positions down only:
// nothing drawn pushes back) and hands triangle meshes to the exporters (OBJ, PLY, VTK) and the
// renderers.
//
// A visual model is a component of the scene file like any other. It acts on the body of its
// node, or of the node named by "object"; models that need no body (a fixed sphere, an organ
// mesh) may sit in any node. VisualScene binds them and updates them when a frame is drawn, not
// at every simulation step.
#pragma once

#include <string>

#include "filum/core/body_component.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/visual/material.hpp"
#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

class VisualModel : public BodyComponent {
 public:
  /// True if the model follows a body (it is then bound to one, see VisualScene).
  virtual bool needsBody() const { return true; }

  /// True for models that draw the body itself (a skin, an implicit surface): a spline that no
  /// such model follows gets a default skin (VisualScene).
  virtual bool drawsBody() const { return false; }

  /// Initialises a model that needs no body (VisualScene calls bind() for the others).
  void initWithoutBody(const Scene& scene) { init(scene); }

  /// Recomputes the meshes from state s (positions down through the model's mapping).
  virtual void update(const SceneState& s) = 0;

  /// False for a model a camera should not frame (a plane's patch, sized after the bodies).
  virtual bool framed() const { return true; }

  /// The meshes of the last update(); most models have one.
  virtual int meshCount() const { return 1; }
  virtual const TriangleMesh& mesh(int index = 0) const = 0;

  /// The fraction of X-rays one layer of the model stops in the fluoroscopy view
  /// (fluoroscopy_view.hpp): the scene's "xray_opacity", else its kind's default.
  double xrayOpacity() const { return material_.xray_opacity >= 0.0 ? material_.xray_opacity : defaultXrayOpacity(); }
  /// The kind's: 0 (not seen: tables, markers) unless the kind says otherwise — metal and the
  /// radiopaque jackets of wires and catheters near 1, contrast-filled vessels faint, soft
  /// tissue fainter.
  virtual double defaultXrayOpacity() const { return 0.0; }

  const Material& material() const { return material_; }
  void setMaterial(const Material& m) { material_ = m; }

 private:
  Material material_;
};

}  // namespace filum::visual
