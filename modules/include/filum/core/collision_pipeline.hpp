// CollisionModel and CollisionPipeline: the kernel's view of the collision side
// (docs/architecture.md, "The three-sided model" and "One step": detectCollisions; paper §3:
// spheres sampled along the spline, penalty response "directly integrated in the system
// equations (2)").
//
// The kernel only knows two small interfaces; everything else (sphere sampling, broad and narrow
// phases, penalty and unilateral responses) lives in the collision library:
//   - CollisionModel: a component of the collision side (spheres on a body, an obstacle, a probe).
//     Scene::init collects them; a scene without any skips collision entirely.
//   - CollisionPipeline: at most one per scene, the component that runs the stages below. It is
//     only called when the scene holds at least one CollisionModel.
// Stage order inside Scene (one step):
//   beginStep(scene, s_n, h)            once, before the integrator: detection at the step's
//                                        start state, the step's contact set;
//   addForce(s, B)                      every integrator stage: contact penalties, B += Q (N);
//   addJacobian(s, kf, df, out)         implicit stages: kf·∂Q/∂q + df·∂Q/∂q̇;
//   addContactRows(s, rows)             every stage: unilateral contacts as inequality rows after
//                                        the constraints' rows; the scene's ConstraintSolver
//                                        solves them all together;
//   takeMultipliers(λ, first)           after that solve: the contact rows' multipliers (forces);
//   missedContact(s_{n+1})              after the integrator: did a centre line pass through
//                                        another, or overlap it deeply, or slide along it further
//                                        than the step's rows follow? If so the scene halves the step.
// The contact set is a function of the step's start state only (no history). The contact solve
// starts from the last step's forces (warm start): the pipeline keeps them in the state's step
// memory (saveMemory, restoreMemory; scene_state.hpp), so a saved and restored SceneState
// continues bit for bit as the run that first left it.
#pragma once

#include "filum/core/block_inverse.hpp"
#include "filum/core/component.hpp"
#include "filum/core/constraint_solver.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/core/types.hpp"

namespace filum {

class MechanicalState;
class Scene;

/// A component of the collision side. Marker interface: its presence switches collision on.
class CollisionModel : public Component {};

class CollisionPipeline : public Component {
 public:
  /// After the state layout is known (Scene::init): bind collision models to bodies, allocate.
  /// Throws SceneError on models that do not fit the scene.
  virtual void init(const Scene& scene) = 0;

  /// Stage 2: collision detection at the start state s of the step (positions, velocities, time).
  /// h: the step (or sub-step, Scene::step halves a step after a pass-through) about to be taken.
  virtual void beginStep(const Scene& scene, const SceneState& s, double h) = 0;

  /// Stage 3a: B += generalized contact forces at stage state s with the step's contact set.
  virtual void addForce(const SceneState& /*s*/, VecX& /*B*/) const {}

  /// Adds k_factor·K + d_factor·D of the contact forces (as ForceField::addJacobian).
  virtual void addJacobian(const SceneState& /*s*/, double /*k_factor*/, double /*d_factor*/,
                           JacobianAccumulator& /*out*/) const {}
  /// True when addJacobian is implemented (implicit integrators require it).
  virtual bool hasJacobian() const { return false; }

  /// Stage 3c: appends the step's unilateral contacts at stage state s to the rows (normal rows
  /// and friction pairs, ConstraintRows::addContactRows). Returns the number of rows added.
  virtual int addContactRows(const SceneState& /*s*/, ConstraintRows& /*rows*/) { return 0; }
  /// The multipliers of the rows it added, starting at row `first` of the solve's λ.
  virtual void takeMultipliers(Eigen::Ref<const VecX> /*lambda*/, int /*first*/) {}
  /// The contacts of the current step's contact set (0: none found at its start).
  virtual int contactCount() const { return 0; }
  /// The abscissas of `body` in the current contact set (adaptive refinement keeps the curve fine
  /// where it is touched). None by default.
  virtual void contactAbscissas(const MechanicalState& /*body*/, std::vector<double>& /*out*/) const {}
  /// True when the pipeline adds contact rows: the scene then needs a ConstraintSolver, and uses
  /// defaultConstraintSolver() when it declares none.
  virtual bool addsContactRows() const { return false; }
  /// What the contact set of a (sub-)step's start missed during it.
  enum class Miss {
    kNone,
    kOverlapOrSlide,   // two centre lines overlapped deeper than the pipeline allows, or a pressed
                       // contact slid further than its rows follow
    kPassThrough,      // a centre line passed through another's (or its own)
    kTooFar,           // the bodies swept so far that the candidate contacts exceeded the
                       // detection's budget (linear in the chords): its contact set is incomplete
  };
  /// After a (sub-)step that began with the last beginStep: whether the motion from that start to
  /// `after` went through a contact its start did not hold — a step too large for the contact set
  /// of its start. The scene then redoes the step in two halves (Scene::advance). Pipelines that
  /// allow pass-through (penalties) return kNone.
  virtual Miss missedContact(const SceneState& /*after*/) { return Miss::kNone; }
  virtual ConstraintSolver* defaultConstraintSolver() { return nullptr; }
  /// Writes what the next detection starts from (the last contacts and forces) into `memory`
  /// (Scene::endStep), and takes it back (Scene::setState): see StepMemory.
  virtual void saveMemory(StepMemory& /*memory*/) const {}
  virtual void restoreMemory(const StepMemory& /*memory*/) {}
};

}  // namespace filum
