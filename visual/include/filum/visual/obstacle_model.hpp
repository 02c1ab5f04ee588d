// ObstacleModel (scene type "ObstacleModel"): an obstacle drawn as what it is, through its
// ObstacleShape (collision/obstacle_shape.hpp) — a plane as a floor patch under the bodies, a
// sphere or a capsule as a shaded solid that follows the obstacle's motion (a probe, a moving
// tool), a triangle mesh (an organ, a cavity) shaded. VisualScene draws every obstacle that no
// ObstacleModel names with one of default colour, so a picture shows the whole scene; a scene
// declares one to choose the colour: "obstacle" (the name of an obstacle of the same node;
// default: the node's only obstacle), "color", "opacity", "resolution" (latitude rings of
// spheres and capsules, default 16).
#pragma once

#include <memory>
#include <string>

#include "filum/collision/obstacle.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class ObstacleModel final : public VisualModel {
 public:
  struct Options {
    std::string obstacle;  // name in the node ("" : the node's only obstacle)
    int resolution = 16;
  };
  explicit ObstacleModel(Options options);
  /// Draws `obstacle` (not owned; must outlive the model) with its kind's default material.
  explicit ObstacleModel(const collision::Obstacle& obstacle);
  static std::unique_ptr<ObstacleModel> fromParams(const Params& p);

  std::string typeName() const override { return "ObstacleModel"; }
  bool needsBody() const override { return false; }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }
  bool framed() const override { return drawn_.kind != collision::ObstacleShape::Kind::kPlane; }
  /// X-ray: a table is not seen, steel probes (spheres, capsules) near opaque, a cavity mesh (a
  /// segmented vessel filled with contrast) faint, a solid organ mesh fainter.
  double defaultXrayOpacity() const override {
    switch (drawn_.kind) {
      case collision::ObstacleShape::Kind::kPlane: return 0.0;
      case collision::ObstacleShape::Kind::kMesh: return drawn_.cavity ? 0.2 : 0.08;
      default: return 0.95;
    }
  }

  /// The obstacle drawn (after init).
  const collision::Obstacle* obstacle() const { return obstacle_; }
  /// The default material of a shape's kind: a pale table, steel tools, tissue-coloured meshes
  /// (translucent when the bodies are inside them).
  static Material defaultMaterial(const collision::ObstacleShape& shape);

 protected:
  void init(const Scene& scene) override;

 private:
  /// The mesh of the obstacle's current shape (planes: a patch around the bodies of `s`).
  void build(const collision::ObstacleShape& shape, const SceneState& s);
  /// A plane's patch: a square centred under the bodies' bounding box, twice its size.
  void buildPlane(const collision::ObstacleShape& shape, const SceneState& s);

  Options options_;
  const collision::Obstacle* obstacle_ = nullptr;
  const Scene* scene_ = nullptr;
  TriangleMesh unit_, mesh_;
  collision::ObstacleShape drawn_;  // the shape mesh_ shows
  bool built_ = false;
  bool explicit_material_ = false;  // "color" or "opacity" given: not the kind's default
  double xray_opacity_ = -1.0;      // "xray_opacity" given (< 0: the kind's)
};

}  // namespace filum::visual
