// CollisionModel and CollisionPipeline: the kernel's view of the collision side (DESIGN.md "The
// three-sided model" and "One time step", stage 2; paper §3: spheres sampled along the spline,
// penalty response "directly integrated in the system equations (2)").
//
// The kernel only knows two small interfaces; everything else (sphere sampling, broad and narrow
// phases, penalty and unilateral responses) lives in the collision library:
//   - CollisionModel: a component of the collision side (spheres on a body, an obstacle, a probe).
//     Scene::init collects them; a scene without any skips collision entirely.
//   - CollisionPipeline: at most one per scene, the component that runs the stages below. It is
//     only called when the scene holds at least one CollisionModel.
// Stage order inside Scene (one step):
//   beginStep(scene, s_n)               once, before the integrator: detection at the step's
//                                        start state, the step's contact set;
//   addForce(s, B)                      every integrator stage: contact penalties, B += Q (N);
//   addJacobian(s, kf, df, out)         implicit stages: kf·∂Q/∂q + df·∂Q/∂q̇;
//   solveContacts(scene, s, L, A⁻¹, a)  every stage, in place of the bilateral constraint solve:
//                                        unilateral contact rows together with the bilateral
//                                        rows L (returns false when it has nothing to add, and
//                                        the scene's ConstraintSolver runs as usual).
// The contact set is a function of the step's start state only (no history), so that a saved
// and restored SceneState continues exactly.
#pragma once

#include "filum/core/block_inverse.hpp"
#include "filum/core/component.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/core/types.hpp"

namespace filum {

class Scene;

/// A component of the collision side. Marker interface: its presence switches collision on.
class CollisionModel : public Component {};

class CollisionPipeline : public Component {
 public:
  /// After the state layout is known (Scene::init): bind collision models to bodies, allocate.
  /// Throws SceneError on models that do not fit the scene.
  virtual void init(const Scene& scene) = 0;

  /// Stage 2: collision detection at the start state s of the step (positions, velocities, time).
  virtual void beginStep(const Scene& scene, const SceneState& s) = 0;

  /// Stage 3a: B += generalized contact forces at stage state s with the step's contact set.
  virtual void addForce(const SceneState& /*s*/, VecX& /*B*/) const {}

  /// Adds k_factor·K + d_factor·D of the contact forces (as ForceField::addJacobian).
  virtual void addJacobian(const SceneState& /*s*/, double /*k_factor*/, double /*d_factor*/,
                           JacobianAccumulator& /*out*/) const {}
  /// True when addJacobian is implemented (implicit integrators require it).
  virtual bool hasJacobian() const { return false; }

  /// Stage 3c with unilateral contacts: on entry a = A⁻¹ b; solves the bilateral rows and the
  /// contact rows of the step's contact set together. Returns false (leaving a untouched) when
  /// there are no unilateral contacts in this step: the scene's ConstraintSolver then runs.
  virtual bool solveContacts(const Scene& /*scene*/, const SceneState& /*s*/, const ConstraintRows& /*bilateral*/,
                             const BlockInverse& /*inverse*/, VecX& /*a*/) {
    return false;
  }
};

}  // namespace filum
