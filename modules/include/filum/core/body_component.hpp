// BodyComponent: a component that acts on one body's MechanicalState (force fields,
// constraints). By default the body is the owner node's; the scene file may name another
// node with "object": "path/to/node".
#pragma once

#include <string>
#include <vector>

#include "filum/core/component.hpp"

namespace filum {

class MechanicalState;
class Scene;
struct SceneState;

class BodyComponent : public Component {
 public:
  const std::string& objectPath() const { return object_path_; }
  void setObjectPath(std::string path) { object_path_ = std::move(path); }

  /// Binds the body (Scene::init) and lets the component precompute its model data.
  void bind(MechanicalState& body, const Scene& scene) {
    body_ = &body;
    init(scene);
  }
  MechanicalState& body() const { return *body_; }
  bool bound() const { return body_ != nullptr; }
  /// Abscissas of the body where this component holds it in state s (a fixed point, a sliding
  /// point, a grasp, a load): adaptive refinement keeps the curve fine there. None by default.
  virtual void actingAbscissas(const SceneState& /*s*/, std::vector<double>& /*out*/) const {}

 protected:
  /// Precompute what never changes (rest lengths, basis tables). Throws SceneError on
  /// parameters that do not fit the body (e.g. fewer samples than needed).
  virtual void init(const Scene& /*scene*/) {}

 private:
  std::string object_path_;
  MechanicalState* body_ = nullptr;
};

}  // namespace filum
