// Scene: the node tree, its settings and its state, and the step pipeline (DESIGN.md
// "One time step"):
//   1. map positions down (later issues: collision and visual sides);
//   2. collision detection, only if collision models exist (later issue);
//   3. per integrator stage: accumulate B (gravity, force fields), solve M A = B, and with
//      constraints the multiplier system L M⁻¹Lᵀ λ = E − L A_t (paper §4);
//   4. check the new state is finite and sane; if not, restore the last good state and report.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/core/block_inverse.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/constraint_solver.hpp"
#include "filum/core/force_field.hpp"
#include "filum/core/integrator.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {

/// Model data of the scene itself: constant during a run.
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

  /// A = f(q, v, t): accelerations of every DOF at state s (all pipeline stages 1–3).
  void computeAcceleration(const SceneState& s, VecX& a);

  /// Kinetic and potential energy at state s.
  Energy energy(const SceneState& s) const;
  /// Position-level violation of every active constraint row.
  VecX constraintViolation(const SceneState& s) const;

  const SceneState& state() const { return state_; }
  /// Replaces the state (e.g. restores a saved one).
  void setState(const SceneState& s) { state_ = s; }
  long stepCount() const { return step_count_; }
  int dofPointCount() const { return point_count_; }

  const std::vector<MechanicalState*>& bodies() const { return bodies_; }
  const std::vector<ForceField*>& forceFields() const { return force_fields_; }
  const std::vector<Constraint*>& constraints() const { return constraints_; }
  Integrator& integrator() const { return *integrator_; }
  ConstraintSolver* constraintSolver() const { return constraint_solver_; }
  /// M⁻¹ body by body (each body's factored mass matrix).
  const BlockInverse& massInverse() const { return mass_inverse_; }
  /// Index in bodies() of the body holding global point p.
  int bodyOfPoint(int p) const;
  /// The body held by the node at path (relative to the root), or nullptr.
  MechanicalState* bodyAt(const std::string& path);

 private:
  void bindBodyComponent(BodyComponent& component);
  /// Names the first non-finite block of v (per body) or returns "".
  std::string findNonFinite(const VecX& v) const;

  class MassInverse final : public BlockInverse {
   public:
    explicit MassInverse(const Scene& scene) : scene_(scene) {}
    void solveBlock(int body, Eigen::Ref<VecX> x) const override;

   private:
    const Scene& scene_;
  };

  std::unique_ptr<Node> root_;
  SceneSettings settings_;
  SceneState state_;
  SceneState last_good_;
  long step_count_ = 0;
  int point_count_ = 0;
  bool initialized_ = false;

  std::vector<MechanicalState*> bodies_;
  std::vector<ForceField*> force_fields_;
  std::vector<Constraint*> constraints_;
  MassInverse mass_inverse_{*this};
  Integrator* integrator_ = nullptr;
  ConstraintSolver* constraint_solver_ = nullptr;

  // Workspace of computeAcceleration (allocated once in init).
  VecX force_;
  ConstraintRows rows_;
  std::string fault_;  // first component that produced non-finite values in this step
};

}  // namespace filum
