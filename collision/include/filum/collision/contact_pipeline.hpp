// ContactPipeline: the collision pipeline of a scene (core/collision_pipeline.hpp;
// docs/architecture.md, "One step": detectCollisions and integrate): detection once per step at
// the step's start state, the response at every integrator stage with that step's contact set.
//
// beginStep (stage 2):
//   1. every SphereCollisionModel resamples its spheres on the current curve and maps centres and
//      velocities down (SphereSamplingMapping);
//   2. thread–obstacle contacts, sphere by sphere against each obstacle (plane, sphere, capsule,
//      triangle mesh, implicit surface, probe) — O(spheres × obstacles), each query bounded;
//   3. thread–thread contacts: the chords between consecutive centres, each in a bounding sphere
//      of its start and predicted end positions (x + v h), go through the uniform-grid broad
//      phase (O(n)); candidate pairs go to the chord narrow phase (narrow_phase.hpp) with
//      continuous detection, so that no contact a step could reach is missed;
//   2b. coaxial instruments: the spheres of an instrument running in a tube (a guidewire in a
//      catheter, SphereCollisionModel "inside") against the tube's centre line, those inside the
//      tube held in its lumen (narrow_phase.hpp, findLumenContacts); step 3 does not seek the
//      chord contacts between the tube and the instrument's chords inside it, which would push
//      the two apart (the parts outside, beyond the tip or beside the tube, meet it as usual);
//   4. the contact set, in a deterministic order (models, spheres and obstacles in declaration
//      order, chord pairs sorted).
// Response (stage 3), "response" in the scene file:
//   "penalty" (paper §3): normal spring and damper, regularized Coulomb friction, added to B at
//      every stage (penalty_contact.hpp), with their Jacobian for implicit integrators;
//   "unilateral": contacts as inequality rows of the scene's constraint solve (addContactRows;
//      constraints/lagrange_multiplier_solver.hpp solves them with the bilateral rows on one
//      Delassus operator by projected Gauss–Seidel) — knots that hold, under explicit and
//      implicit integrators alike. A scene without a ConstraintSolver gets the pipeline's own.
//      Rows per contact, at stage state s, on the anchor w (+ on A's points, − on B's):
//        normal   n·(a_A − a_B) >= −2ω ġ − ω² g       (Signorini at the acceleration level with
//                 Baumgarte's critically damped correction: a resting or speculative contact —
//                 g > 0 but closing, from continuous detection — is held at g >= 0 to within
//                 ġ/(ω e); the contact engages before the chords touch when they close fast);
//        friction t_j·(a_A − a_B) = −ω_f t_j·(v_A − v_B), j = 1, 2, |(λ_t1, λ_t2)| <= μ λ_n
//                 (Coulomb's disc; sticking drives the slip speed to zero at rate ω_f).
//      The rows hold the step's start; a step of a stiff thread can still carry a strand through
//      another when its velocity changes much within the step (a released stiff knot springs at
//      metres per second). After each step the pipeline checks that no centre line passed
//      through another, overlapped it deeply or slid along it faster than the rows follow
//      (missedContact), and the scene redoes such a step in halves.
// Continuous detection assumes each sphere centre moves in a straight line at its start
// velocity over the step; the margin (default r/2) absorbs the curvature of the true motion,
// ½ |a| h² (0.5 mm covers |a| < 1e5 m/s² at h = 1e-4 s).
// The contact set depends on the step's start state only, so save/restore is exact.
#pragma once

#include <memory>
#include <vector>

#include "filum/collision/contact.hpp"
#include "filum/collision/narrow_phase.hpp"
#include "filum/collision/obstacle.hpp"
#include "filum/collision/penalty_contact.hpp"
#include "filum/collision/sphere_collision_model.hpp"
#include "filum/collision/uniform_grid_broad_phase.hpp"
#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "filum/core/collision_pipeline.hpp"
#include "filum/core/params.hpp"

namespace filum::collision {

class ContactPipeline final : public CollisionPipeline {
 public:
  enum class Response { kPenalty, kUnilateral };

  struct Settings {
    Response response = Response::kPenalty;
    PenaltyLaw penalty;         // k (N/m), c (N·s/m), ε (m/s)
    double friction = 0.0;      // μ of thread–thread contacts and of obstacles without their own
    double margin = -1.0;       // m; < 0: half the smallest sphere radius
    bool continuous = true;     // sweep the detection over the step (continuous detection)
    double cell_size = 0.0;     // broad-phase cell (m); 0: twice the largest chord bound
    double stabilization = 0.0;  // ω (1/s) of the normal rows; 0: 0.5/dt
    double friction_rate = 0.0;  // ω_f (1/s) of the friction rows; 0: ω
    double max_penetration = 0.5;  // fraction of R; > 0: a step deepening an overlap beyond it is halved
    double max_slide = 0.0;        // m; > 0: a step sliding a pressed contact further than this is halved
    int contact_halvings = 3;      // ... both down to sub-steps of dt / 2^contact_halvings
  };

  /// What the last detection found (benchmarks, tests, reports).
  struct Statistics {
    int spheres = 0;            // on every thread
    int chords = 0;             // entered in the broad phase
    int candidate_pairs = 0;    // broad-phase pairs of chords
    bool pairs_overflow = false;  // the broad phase stopped at its budget (bodies swept too far)
    int obstacle_contacts = 0;
    int thread_contacts = 0;    // thread–thread (self included)
    int lumen_contacts = 0;     // instruments inside tubes
  };

  explicit ContactPipeline(Settings settings) : settings_(settings) {}

  /// "response": "penalty" (default) or "unilateral"; "stiffness": k (N/m, default 100);
  /// "damping": c (N·s/m, default 0); "friction": μ (default 0); "friction_velocity": ε (m/s,
  /// default 1e-3); "margin": m (default r/2); "continuous": bool (default true); "cell_size": m
  /// (default automatic); "stabilization": ω (1/s, default 0.5/dt); "friction_rate": ω_f (1/s,
  /// default ω); "max_penetration": p, a fraction of the contact distance R (default 0.5; 0: off),
  /// "max_slide": m (default 0: off) and "contact_halvings": k (default 3), see missedContact.
  /// The sweeps of the unilateral solve are the constraint solver's settings
  /// (LagrangeMultiplierSolver "contact_iterations", "contact_tolerance").
  static std::unique_ptr<ContactPipeline> fromParams(const Params& p);

  std::string typeName() const override { return "ContactPipeline"; }
  void init(const Scene& scene) override;
  void beginStep(const Scene& scene, const SceneState& s, double h) override;
  void addForce(const SceneState& s, VecX& B) const override;
  void addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const override;
  bool hasJacobian() const override { return true; }
  int addContactRows(const SceneState& s, ConstraintRows& rows) override;
  void takeMultipliers(Eigen::Ref<const VecX> lambda, int first) override;
  bool addsContactRows() const override { return settings_.response == Response::kUnilateral; }
  ConstraintSolver* defaultConstraintSolver() override { return &default_solver_; }
  /// The last contacts with their forces (the next detection's warm start), 8 numbers each.
  void saveMemory(StepMemory& memory) const override;
  void restoreMemory(const StepMemory& memory) override;
  /// Unilateral response: the centre lines of the step's start (the spheres of beginStep) and of
  /// `after` (the same material points), chords moving linearly in between, tested pair by pair
  /// for a meeting (segment_continuous_collision.hpp) after a swept broad phase: kPassThrough.
  /// kOverlapOrSlide while the (sub-)step is longer than dt / 2^(k−1) (k = "contact_halvings"):
  /// with "max_penetration" p > 0 (default ½: centre lines a radius apart), the step brought two
  /// chords' centre lines closer than (1 − p) R and closer than they were at its start. The rows
  /// hold the contact's material points along the normal of the step's start, which no longer
  /// follows the contact once strands slide around each other by more than about √(2 ρ g) in a
  /// step (ρ the radius of curvature of the strand, g the gap) — a knot pulled at 1 m/s with 1 ms
  /// steps slides 1 mm per step around loops of a few mm, and the rows then both jam the sliding
  /// and let the strands overlap — or threads close like scissors along their length within one
  /// step. The scene redoes such a step in halves (Scene::advance), each with its own detection;
  /// the shortest sub-step is accepted as it is. With "max_slide" > 0, the same when the two
  /// material points of a thread–thread contact that carried a force slid along each other
  /// (relative displacement across the start's normal) further than max_slide: that sliding, not
  /// the overlap it causes, is what the rows do not follow, and it jams a knot pulled fast (the
  /// rows resist the slide through the loops with their fixed normals: the end force of a 2-0
  /// silk knot pulled at 1 m/s reached 1.6-30 N at 1 ms steps, 0.07 N at 0.25 ms).
  /// Instruments inside tubes: kOverlapOrSlide, under the same halving limit, when a sphere that
  /// began the step inside the tube ended it beyond the lumen's wall by more than p (R_in − r)
  /// (the clearance) and further out than it began.
  Miss missedContact(const SceneState& after) override;

  const Settings& settings() const { return settings_; }
  const ContactSet& contacts() const { return contacts_; }
  int contactCount() const override { return static_cast<int>(contacts_.size()); }
  void contactAbscissas(const MechanicalState& body, std::vector<double>& out) const override;
  const Statistics& statistics() const { return stats_; }
  const std::vector<SphereCollisionModel*>& models() const { return models_; }
  const std::vector<Obstacle*>& obstacles() const { return obstacles_; }
  /// The model index of the tube model m runs in, or −1.
  int tubeOf(int m) const { return tube_of_[m]; }

  /// Force on thread point A of contact i at state s (N): the penalty force, or in unilateral
  /// mode the multipliers of the last solve.
  Vec3 contactForce(int i, const SceneState& s) const;
  /// Force the threads exert on obstacle o at state s (N), e.g. for a haptic probe.
  Vec3 obstacleForce(int o, const SceneState& s) const;

 private:
  Settings settings_;
  double margin_ = 0.0;
  double time_step_ = 0.0;
  double scene_dt_ = 0.0;  // the scene's dt (contact halvings)
  std::vector<Vec3> start_offset_;  // max_slide: x_A − x_B of every contact at the step's start
  double stabilization_ = 0.0, friction_rate_ = 0.0;  // ω, ω_f in use
  std::vector<SphereCollisionModel*> models_;
  std::vector<Obstacle*> obstacles_;
  std::vector<int> tube_of_;  // per model: the model of the tube it runs in, or −1
  std::vector<std::vector<TubePlace>> place_;  // per model in a tube: its spheres' places (beginStep)
  // A tube's centre line in blocks for the nearest axis point (findLumenContacts, leftLumen; a
  // workspace, rebuilt at every use: mutable for the const leftLumen).
  mutable AxisBounds axis_bounds_, start_axis_bounds_;
  /// Whether chord k of model a and chord l of model b are a chord of an instrument inside the
  /// tube it runs in, or in its opening, and that tube's: held by the lumen instead, or open
  /// there (no chord contact, no overlap test).
  bool heldInside(int a, int k, int b, int l) const;
  /// Resolves every model's "inside" to the tube's model (SceneError naming the component).
  void findTubes();
  /// missedContact: an instrument's sphere went out through its tube's wall within the step
  /// (after_centers_ at the step's end).
  bool leftLumen() const;
  UniformGridBroadPhase broad_phase_;
  std::vector<BoundingSphere> chords_;
  std::vector<std::pair<int, int>> chord_owner_;  // (model, chord) of every broad-phase entry
  std::vector<IndexPair> pairs_;
  // missedContact: the chords' bounds over the step as taken (centre lines, start to end), and
  // their candidate pairs (findEndPairs).
  std::vector<BoundingSphere> end_chords_;
  std::vector<IndexPair> end_pairs_;
  /// The pairs of end_chords_ whose bounds overlap, into end_pairs_: taken from beginStep's
  /// pairs_ when every end bound lies inside the same chord's bound of beginStep (then every such
  /// pair is among them), else by a new broad phase (false when its budget is spent).
  bool findEndPairs();
  ContactSet contacts_;
  // Unilateral response: row of each contact's normal relative to the first contact row, its
  // directions (n, t1, t2), and the force of the last solve on thread point A.
  std::vector<int> normal_row_;
  std::vector<Vec3> tangent1_, tangent2_;
  std::vector<Vec3> contact_force_;
  // Warm start of the contact rows: the last solve's contacts (keys and forces), sorted.
  struct RememberedContact {
    int model_a, model_b, obstacle;
    double abscissa_a, abscissa_b;
    Vec3 force;
  };
  std::vector<RememberedContact> remembered_;
  /// Moves the last solve's contact forces into remembered_ (before a new detection).
  void rememberForces();
  /// remembered_ in the order rememberedForce searches.
  void sortRemembered();
  bool restored_ = false;  // remembered_ was restored (restoreMemory): the next beginStep keeps it
  /// The remembered force of the same contact in the last solve, or zero.
  Vec3 rememberedForce(const Contact& c) const;
  constraints::LagrangeMultiplierSolver default_solver_;
  std::vector<Points> after_centers_;  // missedContact: sphere centres at the step's end, per model
  Statistics stats_;
};

}  // namespace filum::collision
