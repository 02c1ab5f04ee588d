// VisualScene: the visual side of a loaded scene — every VisualModel of the node tree, bound to
// its body (its node's, or the node named by "object"), plus a default skin
// (GeneralizedCylinder with the spline's radius) for each DynamicSpline that no skin or surface
// follows, and an ObstacleModel in its kind's colours for each obstacle that no ObstacleModel names
// (visual/obstacle_model.hpp), and a sphere at the target of every point constraint no SphereModel
// marks, so that every scene can be drawn and exported whole. update(s) maps positions down for the
// frame being drawn (not at every simulation step).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/core/scene.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class VisualScene {
 public:
  /// Binds the models of `scene` (which must outlive this object). Throws SceneError naming the
  /// model at fault (no such node, no body where one is needed, a body of the wrong kind).
  explicit VisualScene(Scene& scene);

  /// Recomputes every model's meshes from state s.
  void update(const SceneState& s);

  const std::vector<VisualModel*>& models() const { return models_; }
  /// Draws `body` by `model` (not owned; it must outlive this object) instead of its default skin,
  /// if it had one: a model the scene file cannot name (a wound's lip, drawn as the slab beside its
  /// edge by visual/wound_visual.hpp). The model joins models() — pictures, meshes and bounds —
  /// under the name `name` (made unique).
  void drawBodyWith(const MechanicalState& body, VisualModel& model, const std::string& name);
  /// A unique, file-name-safe name per model: "<node path>_<model name>" with '/' and spaces as '_'.
  const std::string& modelName(std::size_t i) const { return names_[i]; }
  /// Bounds of every vertex of the last update (false if there is none), without the models that
  /// only show where things are bounded (a plane's patch: VisualModel::framed).
  bool bounds(Vec3& lower, Vec3& upper) const;

 private:
  Scene& scene_;
  long layout_revision_ = 0;  // the scene's layout the models are bound to (Scene::refine)
  std::vector<VisualModel*> models_;
  std::vector<std::string> names_;
  /// Draws the obstacles no ObstacleModel names, in their kinds' default colours.
  void addObstacleDefaults(Scene& scene);
  /// Marks the target of every point constraint no SphereModel marks (a grip, a fixed point, a
  /// needle hole), hidden once it lets go.
  void addTargetMarkers(Scene& scene);

  std::vector<std::unique_ptr<VisualModel>> defaults_;  // default skins and obstacles (not in the node tree)
};

}  // namespace filum::visual
