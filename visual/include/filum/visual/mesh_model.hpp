// MeshModel (scene type "MeshModel"): a rigid triangle mesh read from a file — an organ, a
// vessel tree, a tissue pad — drawn and exported with the bodies. "file" (.obj, .off, .ply or
// .stl, read by geometry/mesh_file.hpp; relative to the scene file), "units" ("m", "cm" or "mm":
// the unit of the file's coordinates, default "m") and "scale" (default 1), which multiply
// (geometry/mesh_units.hpp), "rotation" ([rx, ry, rz] in degrees, applied about x, then y, then
// z), "translation" (m), "color", "opacity". The file is read when the scene is loaded: a
// missing or malformed file is a scene error naming the file and the JSON path.
#pragma once

#include <memory>

#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class MeshModel final : public VisualModel {
 public:
  /// mesh: already placed in the world (m), with normals.
  explicit MeshModel(TriangleMesh mesh) : mesh_(std::move(mesh)) {}
  static std::unique_ptr<MeshModel> fromParams(const Params& p);

  std::string typeName() const override { return "MeshModel"; }
  /// X-ray: an organ: soft tissue, barely seen.
  double defaultXrayOpacity() const override { return 0.08; }
  bool needsBody() const override { return false; }
  void update(const SceneState&) override {}
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

 private:
  TriangleMesh mesh_;
};

}  // namespace filum::visual
