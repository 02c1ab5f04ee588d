// Scene: the node tree, its settings and its state, and the step pipeline (docs/architecture.md,
// "One step"):
//   1. map positions down (the collision models at detection, the visual models after the step);
//   2. collision detection, only if collision models exist (CollisionPipeline::beginStep, see
//      collision_pipeline.hpp; the collision library implements it);
//   3. per integrator stage: accumulate B (gravity, force fields), solve M A = B, and with
//      constraints the multiplier system L M⁻¹Lᵀ λ = E − L A_t (paper §4);
//   4. check the new state is finite and sane; if not, restore the last good state and report.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "filum/core/block_inverse.hpp"
#include "filum/core/collision_pipeline.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/constraint_solver.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/integrator.hpp"
#include "filum/core/layout_controller.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/core/stage_times.hpp"

namespace filum {

class CurveBody;

/// Model data of the scene itself: constant during a run.
/// Limits of the time stepping, checked when a scene is loaded and when `filum run -t` overrides
/// the duration (scene_loader.cpp, run_command.cpp).
///  - dt >= 1e-9 s: the stiffest reference material (2 GPa, 910 kg/m³: waves at 1.5 km/s) on
///    control points 0.1 mm apart is stable explicitly below 7e-8 s; a smaller step only piles
///    up steps and round-off;
///  - dt <= 1 s: gravity alone moves a point 5 m in one such step;
///  - at most 1e8 steps per run: `filum run` keeps each step's wall time (8 bytes) for its
///    timing summary (800 MB at the limit), and 1e8 steps of the smallest scene take hours;
///  - duration >= dt / 2: a shorter run rounds to zero steps.
inline constexpr double kMinTimeStep = 1e-9;
inline constexpr double kMaxTimeStep = 1.0;
inline constexpr long kMaxSteps = 100000000;

/// "" when a run of `duration` at `dt` has between 1 and kMaxSteps steps; otherwise what was
/// found ("0 steps (duration 1e-05 s < dt / 2)", ...). dt is within its limits.
std::string stepCountProblem(double duration, double dt);

struct SceneSettings {
  std::string name = "scene";
  std::string source;              // file it was loaded from
  double dt = 1e-4;                // time step (s)
  double duration = 1.0;           // default run length (s)
  Vec3 gravity{0.0, 0.0, -9.81};   // (m/s²)
  double max_speed = 1.0e3;        // a DOF faster than this (m/s) means divergence
};

/// Outcome of one Scene::step().
struct StepReport {
  bool ok = true;
  long step = 0;          // index of the step that was attempted
  double time = 0.0;      // simulated time at the start of that step (s)
  std::string culprit;    // component description when !ok
  std::string message;    // what went wrong when !ok
};

struct Energy {
  double kinetic = 0.0;    // J
  double potential = 0.0;  // J (gravity + elastic)
  double total() const { return kinetic + potential; }
};

class Scene {
 public:
  Scene();
  Node& root() { return *root_; }
  const Node& root() const { return *root_; }
  SceneSettings& settings() { return settings_; }
  const SceneSettings& settings() const { return settings_; }

  /// Binds components to bodies, lays out the state, checks the assembly. Throws SceneError
  /// naming the component at fault.
  void init();

  /// One time step of settings().dt. On divergence the state is rolled back to the state
  /// before the step and the report says which step and component.
  StepReport step();

  /// A = f(q, v, t): accelerations of every DOF at state s (all pipeline stages 1–3):
  /// computeForce, M⁻¹ body by body, applyConstraints with the mass inverse.
  void computeAcceleration(const SceneState& s, VecX& a);

  // The pieces of computeAcceleration, for integrators that solve their own system (implicit
  // steps solve (M − θh D − κh² K) a = b and constrain a through that matrix's inverse).

  /// Stage 3, forces: B = generalized forces at s, gravity and every force field (3N, N).
  void computeForce(const SceneState& s, VecX& B);
  /// Stage 3, constraints: on entry a = A⁻¹ b (unconstrained); on exit the a that solves A a = b + Lᵀλ,
  /// L a = E for the active constraints' rows built at state s. `inverse` applies A⁻¹: the mass
  /// matrix for explicit steps, the step matrix for implicit ones. No-op without constraints.
  /// The step's unilateral contacts (CollisionPipeline::addContactRows) are rows of the same
  /// solve, as inequalities.
  void applyConstraints(const SceneState& s, const BlockInverse& inverse, VecX& a);
  /// Which force Jacobians addForceJacobian adds: all of them, only the constant ones
  /// (ForceField::jacobianIsConstant), or only those that change with the state (contacts too).
  enum class JacobianTerms { kAll, kConstant, kVarying };
  /// Adds k_factor·K + d_factor·D of the force fields (and contact penalties) at s.
  void addForceJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out,
                        JacobianTerms terms = JacobianTerms::kAll) const;
  /// Adds factor·(M ⊗ I₃) of every body.
  void addMassMatrix(double factor, JacobianAccumulator& out) const;
  /// Records what went wrong in the current step (e.g. an integrator's failed factorization);
  /// the first fault wins, and step() rolls back and reports it.
  void noteFault(const std::string& message) {
    if (fault_.empty()) fault_ = message;
  }
  /// The fault recorded in the current step so far ("" if none).
  const std::string& fault() const { return fault_; }
  /// Takes back the fault recorded by a trial that its caller discards — an implicit step's Newton
  /// attempt that is taken again in halves (implicit_step_solver.hpp): the step goes on clean, and
  /// the caller reports the message if the step fails in the end.
  std::string takeFault() { return std::exchange(fault_, std::string()); }

  /// Kinetic and potential energy at state s.
  Energy energy(const SceneState& s) const;
  /// Position-level violation of every active constraint (Constraint::violationCount()
  /// entries each, in declaration order).
  VecX constraintViolation(const SceneState& s) const;

  const SceneState& state() const { return state_; }
  /// Replaces the state (e.g. restores a saved one); scheduled releases follow its time, and the
  /// components take back the step memory it carries (SceneState::memory), so that the run from
  /// a restored state repeats bit for bit the run that first left it.
  void setState(const SceneState& s);
  long stepCount() const { return step_count_; }

  /// Inserts control points into `body` at the abscissas (its curve unchanged: CurveBody::refine)
  /// between two steps, and lays the scene out anew in one call: every body keeps its motion
  /// (the refined one q̃ = A q, ṽ = A v), time and the constraints' extra DOFs are kept, and
  /// force fields, constraints and the collision pipeline are bound to the new layout (their
  /// rows, mappings and contact sets are rebuilt); the step matrix lays itself out at its next
  /// assembly. Visual models follow through CurveBody::layoutRevision. Throws SceneError when
  /// the body cannot be refined (nothing changed then). A saved SceneState of the old layout no
  /// longer fits (setState refuses it).
  void refine(CurveBody& body, const std::vector<double>& abscissas);
  /// Removes the control point of `body` whose knot is at the abscissa when the curve moves by
  /// at most `tolerance` (m; CurveBody::coarsen), and lays the scene out anew as refine does.
  /// Returns false, with nothing changed, when the removal would move the curve further.
  bool coarsen(CurveBody& body, double abscissa, double tolerance);
  /// Cuts `body` at the abscissa (CurveBody::cut: two strands that move apart from now on) and
  /// lays the scene out anew as refine does: constraints and contacts keep their abscissas, so a
  /// point held on either side stays held. Throws SceneError when the body cannot be cut there
  /// (nothing changed then).
  void cut(CurveBody& body, double abscissa);
  /// A body torn where its tension exceeded its strength (ForceField::tearsAt), cut at the start
  /// of the step after.
  struct Rupture {
    double time = 0.0;      // s (the start of the step that applied the cut)
    std::string body;       // its description
    double abscissa = 0.0;
    double tension = 0.0;   // N, at the end of the step before
  };
  /// Every rupture since init, in order.
  const std::vector<Rupture>& ruptures() const { return ruptures_; }
  /// Counts layout changes (refine, coarsen, cut): 0 for a scene that never changed its points.
  long layoutRevision() const { return layout_revision_; }
  /// What the constraint solver sees of the scene (constraint_problem.hpp): the bodies' blocks of
  /// points and the sizes, rebuilt when the layout changes.
  const ConstraintProblem& constraintProblem() const;
  /// Steps redone in halves because the contact set of their start missed a contact
  /// (CollisionPipeline::missedContact: a pass-through, a deep overlap or a fast slide; since init).
  long contactHalvings() const { return contact_halvings_; }
  /// Steps redone in halves because a contact solve did not reach its tolerance (since init).
  long solveHalvings() const { return solve_halvings_; }
  /// Sub-steps integrated since init, those redone in halves included (one per step when no
  /// step was ever halved).
  long substeps() const { return substeps_; }
  /// Wall time spent in each stage of the steps since the scene was built (stage_times.hpp).
  const StageTimes& stageTimes() const { return stage_times_; }
  int dofPointCount() const { return point_count_; }
  /// Groups of the implicit step matrix (JacobianAccumulator): the points, then the bodies'
  /// internal DOFs in triples.
  int stepGroupCount() const { return point_count_ + internal_velocity_count_ / 3; }
  /// Number E of extra scalar DOFs (constraints' own, after the 3N point coordinates).
  int extraDofCount() const { return extra_count_; }
  /// Sizes of q and of v (and of forces and accelerations): 3N + E + the bodies' internal DOFs
  /// (scene_state.hpp); equal unless a body has more internal positions than velocities.
  int positionSize() const { return 3 * point_count_ + extra_count_ + internal_position_count_; }
  int velocitySize() const { return 3 * point_count_ + extra_count_ + internal_velocity_count_; }
  /// True when some body has internal DOFs (MechanicalState::internalVelocityCount() > 0).
  bool hasInternalDofs() const { return internal_velocity_count_ > 0 || internal_position_count_ > 0; }

  /// q1 = q0 ⊕ h w: positions moved along the velocity-layout vector w for a time h — q + h w for
  /// points and extra DOFs, each body's integrateInternal for its internal DOFs (a rotation
  /// turned by h ω). q1 may be q0. The integrators advance positions through it (the implicit ones
  /// add h v to q directly when the scene has no internal DOFs: the same for points and extras).
  void integratePositions(const VecX& q0, const VecX& w, double h, VecX& q1) const;

  const std::vector<MechanicalState*>& bodies() const { return bodies_; }
  const std::vector<ForceField*>& forceFields() const { return force_fields_; }
  const std::vector<Constraint*>& constraints() const { return constraints_; }
  const std::vector<LayoutController*>& layoutControllers() const { return layout_controllers_; }
  /// Abscissas of `body` where something holds or touches it now: its constraints' and force
  /// fields' points (BodyComponent::actingAbscissas) and its contacts (CollisionPipeline::
  /// contactAbscissas). Appended to out.
  void actingAbscissas(const MechanicalState& body, std::vector<double>& out) const;
  /// Control points inserted and removed by layout controllers since init.
  long adaptiveInsertions() const { return adaptive_insertions_; }
  long adaptiveRemovals() const { return adaptive_removals_; }
  Integrator& integrator() const { return *integrator_; }
  ConstraintSolver* constraintSolver() const { return constraint_solver_; }
  /// The multipliers of `constraint`'s rows in the last constraint solve (Lᵀλ is its force on the
  /// bodies: for a point constraint Σ λ_i d_i, N); empty when it was not active then, or without
  /// a solve. The last solve is the integrator's: an implicit step's accepted iterate; an explicit
  /// one's at its last stage's state (RK4: the fourth, not the step's weighted force).
  Eigen::Ref<const VecX> constraintMultipliers(const Constraint& constraint) const;
  /// The collision pipeline, or nullptr when the scene holds no CollisionModel (collision is
  /// then skipped entirely).
  CollisionPipeline* collisionPipeline() const { return collision_; }
  /// M⁻¹ body by body (each body's factored mass matrix).
  const BlockInverse& massInverse() const { return mass_inverse_; }
  /// Index in bodies() of the body holding global point p.
  int bodyOfPoint(int p) const;
  /// The body held by the node at path (relative to the root), or nullptr.
  MechanicalState* bodyAt(const std::string& path) const;

 private:
  /// B += gravity (and the bodies' own forces on their internal DOFs), force fields, contact
  /// penalties and known constraint forces at s. With name_non_finite: stops at the first source
  /// after which B is not finite and returns a message naming it ("" otherwise).
  std::string addForces(const SceneState& s, VecX& B, bool name_non_finite) const;

  void bindBodyComponent(BodyComponent& component);
  /// Names the first non-finite block of v (per body) or returns "".
  std::string findNonFinite(const VecX& v) const;

  class MassInverse final : public BlockInverse {
   public:
    explicit MassInverse(const Scene& scene) : scene_(scene) {}
    void solveBlock(int body, Eigen::Ref<VecX> x) const override;
    bool sameOnEveryAxis() const override { return true; }  // M ⊗ I₃ (paper eq. 3)
    // M is factored once per layout (Scene::refine factors a refined body's M again).
    long revision() const override { return scene_.layout_revision_; }

   private:
    const Scene& scene_;
  };

  std::unique_ptr<Node> root_;
  SceneSettings settings_;
  SceneState state_;
  SceneState last_good_;
  // The step pipeline (docs/architecture.md, "One step"), one function per stage; step() runs
  // beginStep, advance (detectCollisions, integrate, again in halves for missed contacts) and
  // endStep.
  /// Applies the events due at the step's start (scheduled refinements and cuts of bodies, then
  /// releases of constraints) and keeps the last good state. A layout change that fails is the
  /// step's fault (reported, nothing advanced).
  void beginStep();
  /// The components' step memory into state_.memory (after a step that succeeded), and back from
  /// it (setState, rollback).
  void saveMemory();
  void restoreMemory();
  /// Control points scheduled for insertion, and cuts (CurveBody::layoutChangeDue), at this step.
  void applyScheduledLayoutChanges();
  /// Bodies whose tension exceeds their strength (ForceField::tearsAt) cut where it does.
  void applyRuptures();
  /// The plans of the layout controllers that are due (LayoutController).
  void applyLayoutControllers();
  std::vector<LayoutController*> layout_controllers_;
  LayoutController::Plan plan_;
  long adaptive_insertions_ = 0, adaptive_removals_ = 0;
  std::vector<Rupture> ruptures_;
  /// Advances state_ by one step dt as 2^d sub-steps of halving depth d, d the depth the last
  /// step needed (StepMemory::substep_depth), and leaves there the depth the next step starts at.
  void advanceStep(double dt);
  /// Advances state_ by h (detection at its start, then the integrator); redone as two halves,
  /// recursively, while the collision pipeline finds a contact the step's contact set missed.
  void advance(double h, int depth);
  /// Stages 1–2 at the (sub-)step's start: the collision models map the positions down and
  /// detect the contact set; force fields see the start state (ForceField::beginStep).
  void detectCollisions(double h);
  /// Stage 3: the integrator. Each of its evaluations calls computeForce (gravity, force
  /// fields, contact penalties, mapped forces up through Jᵀ) and applyConstraints (constraints
  /// and contacts by the one constraint solver), then integrates.
  void integrate(double h);
  /// Stage 4: a non-finite or too fast state is rolled back and reported; else the step counts.
  StepReport endStep(StepReport report);
  static constexpr int kMaxContactHalvings = 6;
  static constexpr int kMaxSolveHalvings = 3;  // an unconverged contact solve: down to dt / 8
  static constexpr int kMaxRememberedDepth = 3;  // a step starts at dt / 8 at the shortest (advanceStep)
  std::vector<SceneState> substep_start_;  // one per halving depth (sized at init)
  long contact_halvings_ = 0;
  long solve_halvings_ = 0;
  StageTimes stage_times_;  // wall time per stage (stageTimes)
  long substeps_ = 0;       // sub-steps taken (accepted or redone), every step's included
  int deepest_depth_ = 0;   // the deepest halving depth the current step reached
  /// The (sub-)step of length h at halving depth `depth` taken again from its start, as two halves.
  void redoInHalves(double h, int depth);
  /// Contact solves of the constraint solver that did not converge, since its construction.
  long unconvergedContactSolves() const;
  long layout_revision_ = 0;
  /// Binds force fields, constraints and the collision pipeline to the bodies' current layout
  /// again (refine).
  void bindComponents();
  /// After `body` changed its points by q̃ = A q (A: new × old), before anything else moved:
  /// new offsets, the state carried over from the old layout, the components bound again.
  void relayout(const CurveBody& body, const SparseMatrix& A);
  /// Extra DOF indices of the constraints after the 3N point coordinates.
  void setExtraIndices();
  /// Finds the collision pipeline and binds it (Scene::init).
  void initCollision();
  /// Buffers sized by the layout: forces, the last good state, the sub-step starts.
  void resizeWorkspace();
  long step_count_ = 0;
  int point_count_ = 0;
  int extra_count_ = 0;  // extra DOFs of constraints (scene_state.hpp)
  int internal_position_count_ = 0, internal_velocity_count_ = 0;  // bodies' internal DOFs
  /// Internal blocks after the points and extra DOFs, body by body (scene_state.hpp).
  void setInternalOffsets();
  mutable VecX internal_increment_;  // h w of one body's internal block (integratePositions, energy)
  bool initialized_ = false;

  std::vector<MechanicalState*> bodies_;
  std::vector<ForceField*> force_fields_;
  std::vector<Constraint*> constraints_;
  MassInverse mass_inverse_{*this};
  Integrator* integrator_ = nullptr;
  ConstraintSolver* constraint_solver_ = nullptr;
  mutable ConstraintProblem constraint_problem_;  // refreshed by constraintProblem()
  CollisionPipeline* collision_ = nullptr;  // null unless collision models exist

  // Workspace of computeAcceleration (allocated once in init).
  VecX force_;
  ConstraintRows rows_;
  std::vector<int> constraint_first_row_;  // each constraint's first row in rows_ (−1: inactive)
  std::string fault_;  // first component that produced non-finite values in this step
};

}  // namespace filum
