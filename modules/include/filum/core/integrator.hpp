// Integrator: advances the scene state by one time step using the scene's accelerations
// A = f(q, v, t) (Scene::computeAcceleration), or, for implicit schemes, the pieces of it
// (Scene::computeForce, Scene::addForceJacobian, Scene::addMassMatrix, Scene::applyConstraints).
#pragma once

#include <string>

#include "filum/core/component.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

class Scene;

class Integrator : public Component {
 public:
  /// Advances s from t to t + dt (s.time included).
  virtual void step(Scene& scene, SceneState& s, double dt) = 0;
  /// Global order of accuracy in dt (for convergence tests and reports).
  virtual int order() const = 0;
  /// True for schemes that use the force Jacobian (ForceField::addJacobian): the scene then
  /// refuses, at init, force fields that do not provide one.
  virtual bool needsJacobians() const { return false; }
  /// Why this scheme does not step bodies with internal DOFs (the scene refuses them at init),
  /// or "" when it does.
  virtual std::string internalDofsRefusal() const { return ""; }
  /// Writes what the next step depends on beyond q and v (a kept factorization, the reuse
  /// schedule) into `memory` (Scene::endStep), and takes it back (Scene::setState).
  virtual void saveMemory(StepMemory& /*memory*/) const {}
  virtual void restoreMemory(const Scene& /*scene*/, const StepMemory& /*memory*/) {}
};

}  // namespace filum
