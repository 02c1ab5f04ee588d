// Wound: a skin incision to be sutured — two lips that move under the suture's pull, and the holes
// a curved needle (needle.hpp) punctures in them, through which the thread then slides.
//
//   "wound": {"lips": ["left lip", "right lip"], "thread": "suture", "normal": [0, 0, 1],
//             "width": 0.015, "thickness": 0.005, "edge_radius": 0.001, "puncture_force": 1.0,
//             "indentation_stiffness": 1000, "holes_per_lip": 2, "friction": 5e-4,
//             "engage_distance": 1.5e-3}
//
// Lips. Each lip is a curve body of the scene file running along the wound's edge (a DynamicSpline
// with the tissue's stretching and bending, held where it lies by a TissueAttachment: the tissue
// around it): the axis of the lip's rounded edge, edge_radius r_e inside both its cut face and the
// skin. Lip k is the slab beside its edge curve P_k(s): with s* the closest point of x on the edge
// (0 < s* < 1), t̂ the edge's unit tangent there, n̂ the skin's outward normal made ⊥ t̂, and
// ô = ± n̂ × t̂ pointing away from the other lip,
//   u = (x − P_k(s*))·ô + r_e,  v = −(x − P_k(s*))·n̂ + r_e,
//   x lies in lip k  ⇔  0 <= u <= width  and  0 <= v <= thickness.
// The slab moves with its edge: the part of the lip a suture pulls is near the wound. With a
// SphereCollisionModel of radius r_e on each lip (and a ContactPipeline), the lips meet at their
// cut faces and press on each other; the slabs are an obstacle for the thread (wound_pad.hpp)
// except where it runs in the tissue between its holes.
//
// Puncture. A needle's tip that enters a lip from outside presses on it: the skin resists with
// F = k_i δ, δ the tip's depth past the point e where it entered, along the entered face's inward
// normal (k_i: "indentation_stiffness", N/m). Once F reaches the puncture force the skin gives
// way and e becomes a hole (entry). A tip that leaves the lip it went into makes a hole where it
// leaves (exit; the skin is not resisting from inside). A tip drawn back before puncturing makes
// nothing. Crossings are found by bisection on the segment between the tip's positions at
// consecutive steps (the tip moves about 0.1 mm per step).
//
// Holes. A hole is fixed in its lip: X(t) = P_k(s_h, t) + o, o = e − P_k(s_h) at the puncture (it
// translates with the edge; its turn is neglected, point_target.hpp). The needle runs along its own
// arc through the holes it made; once a hole is behind its swage (the hole's angle in the needle's
// plane, from the swage towards the tip, below −engage_distance / R: the swage is that far past it),
// the thread swaged to it runs through the hole:
// the thread's point nearest to X within 5 mm of the swage, if it is within engage_distance (else
// the hole holds nothing, and says so), is where a sliding point
// (constraints/sliding_point_constraint.hpp) engages there: s(t) starts at that abscissa and ṡ at
// the thread's sliding rate through the hole, tᵀ(Ẋ − Ṗ(s)) / |t|². From then on the thread slides
// through the hole with viscous friction η ("friction", N·s/m) and the hole's reaction pulls the
// lip. The sliding points are made when the scene is built, holes_per_lip per lip, inactive until
// engaged (their abscissas are DOFs of the state, sized once); a thread slid out of its hole
// releases it, and the slot stays used.
//
// What is not modelled (yet): the lip's deformation by the pressing tip (the force is reported,
// the lip does not dent), the needle's drag in the tissue and its contact with the skin, the
// exemption of the thread in the tissue from the lips' edge spheres (a bite must be deeper than
// the edge's radius).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/params.hpp"
#include "filum/core/scene.hpp"
#include "filum/haptics/needle.hpp"
#include "filum/haptics/wound_pad.hpp"

namespace filum::constraints {
class SlidingPointConstraint;
}

namespace filum::haptics {

class Wound {
 public:
  struct Settings {
    std::string lips[2];              // node paths of the lips' edge curves
    std::string thread;               // node path of the suture
    Vec3 normal = Vec3(0, 0, 1);      // n̂, the skin's outward normal
    double width = 0.015;             // m, each lip's extent away from the wound
    double thickness = 0.005;         // m
    double edge_radius = 0.0;         // r_e (m), the edge curve's depth inside the cut face and skin
    double puncture_force = 1.0;      // N
    double indentation_stiffness = 1000.0;  // N/m
    int holes_per_lip = 2;
    double friction = 5e-4;           // N·s/m
    double engage_distance = 1.5e-3;  // m
  };
  static constexpr int kMaxHolesPerLip = 64;

  /// The "wound" block; throws SceneError at the faulty field (a lip or thread that is not a
  /// curve body of `scene`, a lip named twice or as the thread).
  static Settings settingsFromParams(const Params& p, const Scene& scene);

  explicit Wound(Settings settings);
  const Settings& settings() const { return settings_; }

  /// Adds the sliding points (inactive) to the thread's node; the caller binds the scene again.
  /// `origin`: the JSON place of the block, for messages.
  void attach(Scene& scene, const std::string& origin);
  /// After the scene is bound: the lips' sides (ô away from the other lip) at the start.
  void bind(const Scene& scene);
  /// The skin as an obstacle of the thread (added to the scene's root by attach).
  const WoundPad& pad() const { return *pad_; }

  /// Follows each needle's tip at the scene's state (the step's start): presses, punctures and
  /// exits; engages sliding points where the thread has passed a hole. Returns one line per event
  /// (without its time).
  std::vector<std::string> follow(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles);

  struct Hole {
    int lip = 0;
    double lip_abscissa = 0.0;    // s_h on the lip's edge
    Vec3 offset = Vec3::Zero();   // o (m)
    bool entry = true;            // made going in (else coming out)
    double time = 0.0;            // s, when the needle made it
    int needle = 0;
    double from_edge = 0.0;       // (e − P_k)·ô at the puncture (m): the bite's width
    int slot = -1;                // its sliding point (index into slots); −1: not engaged yet, −2: the
                                  // thread passed it too far away, −3: no sliding point was free
  };
  const std::vector<Hole>& holes() const { return holes_; }
  /// X(t) of hole h at state s (m).
  Vec3 holePosition(const SceneState& s, const Hole& h) const;
  /// The sliding points, lip by lip (holes_per_lip each).
  const std::vector<constraints::SlidingPointConstraint*>& slots() const { return slots_; }

  /// The force the skin pushes back on needle k's tip while it presses (N, 0 otherwise); without
  /// an index, the largest over the needles.
  double pressingForce(int needle) const;
  double pressingForce() const;
  /// How many sliding points hold the thread now (engaged, not slid out).
  int holdingHoles() const;
  /// After a step: the gap's smallest and last values; one line per hole the thread slid out of.
  std::vector<std::string> afterStep(const SceneState& s);
  /// metrics.json's "wound": holes made (lip, entry or exit, time, distance from the edge (m)),
  /// how many hold the thread, the peak force on the needle before a puncture (N), the gap at the
  /// start, its smallest and its last (m).
  nlohmann::json summary() const;
  /// The largest of them so far (N).
  double peakForce() const { return peak_force_; }

  /// Lip k at state s: whether x lies in it, and its local coordinates.
  struct LipPoint {
    bool inside = false;
    double s = 0.0;       // closest abscissa on the edge
    double across = 0.0;  // (x − P)·ô (m)
    double depth = 0.0;   // −(x − P)·n̂ (m)
    Vec3 edge = Vec3::Zero(), tangent = Vec3::Zero(), normal = Vec3::Zero(), outward = Vec3::Zero();
  };
  LipPoint locate(const SceneState& s, int lip, const Vec3& x) const;
  /// The lip's edge curve.
  const CurveBody& lip(int k) const { return *lips_[k]; }
  /// ô's sign of lip k (+1: n̂ × t̂ points away from the other lip).
  double side(int k) const { return side_[k]; }
  /// The gap between the lips' cut faces at the middle of lip 0 (m): the distance from P_0(½)
  /// across to lip 1's edge curve, along ô_0's opposite, less 2 r_e.
  double gap(const SceneState& s) const;

 private:
  struct Tip {
    bool started = false;
    Vec3 previous = Vec3::Zero();
    int in_lip = -1;        // punctured into this lip
    int pressing = -1;      // pressing on this lip, not yet punctured
    Vec3 entered = Vec3::Zero();  // e (m), where it entered the lip it presses on
    Vec3 inward = Vec3::Zero();   // the entered face's inward normal
    double force = 0.0;     // N
  };
  /// The point between a (in lip k: `inside_a`) and b (the other way) on the lip's boundary.
  Vec3 crossing(const SceneState& s, int lip, Vec3 a, Vec3 b, bool inside_a) const;
  void makeHole(const SceneState& s, int lip, const Vec3& at, bool entry, int needle, std::vector<std::string>& events);
  /// The pad where the lips are at state s, and the thread's spans in the tissue.
  void updatePad(const SceneState& s, const std::vector<std::unique_ptr<Needle>>& needles);
  void engage(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles, std::vector<std::string>& events);
  /// The thread's abscissa nearest to X within 5 mm of the needle's swage.
  double threadAtHole(const SceneState& s, const Needle& needle, const Vec3& X) const;

  Settings settings_;
  const CurveBody* lips_[2] = {nullptr, nullptr};
  const CurveBody* thread_ = nullptr;
  double side_[2] = {1.0, 1.0};
  std::vector<constraints::SlidingPointConstraint*> slots_;
  std::vector<char> slot_used_;  // 0 free, 1 holding, 2 let go
  std::vector<Hole> holes_;
  std::vector<Tip> tips_;
  WoundPad* pad_ = nullptr;  // owned by the scene's root node
  double peak_force_ = 0.0;
  double gap_start_ = 0.0, gap_min_ = 0.0, gap_last_ = 0.0;
};

}  // namespace filum::haptics
