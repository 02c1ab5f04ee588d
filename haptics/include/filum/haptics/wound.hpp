// Wound: a skin incision to be sutured — two lips that move under the suture's pull, and the holes
// a curved needle (needle.hpp) punctures in them, through which the thread then slides.
//
//   "wound": {"lips": ["left lip", "right lip"], "thread": "suture", "normal": [0, 0, 1],
//             "width": 0.015, "thickness": 0.005, "edge_radius": 0.001, "puncture_force": 1.0,
//             "indentation_stiffness": 1000, "holes_per_lip": 2, "friction": 5e-4,
//             "engage_distance": 1.5e-3, "targets": [[x, y, z], ...]}
//
// Lips. Each lip is a curve body of the scene file running along the wound's edge (a DynamicSpline
// with the tissue's stretching and bending, held where it lies by a TissueAttachment: the tissue
// around it): the axis of the lip's rounded edge, edge_radius r_e inside both its cut face and the
// skin. Lip k is the slab beside its edge curve P_k(s): with s* the closest point of x on the edge
// (0 < s* < 1), t̂ the edge's unit tangent there, n̂ the skin's outward normal made ⊥ t̂, and
// ô = ± n̂ × t̂ pointing away from the other lip,
//   u = (x − P_k(s*))·ô + r_e  (across, from the cut face),  v = −(x − P_k(s*))·n̂ + r_e  (depth),
//   x lies in lip k  ⇔  0 <= u <= width  and  0 <= v <= thickness.
// The slab moves with its edge: the part of the lip a suture pulls is near the wound. Each lip
// carries a SphereCollisionModel of radius r_e, so that the lips meet at their cut faces and press
// on each other; the slabs are an obstacle for the thread (wound_pad.hpp) except where it runs in
// the tissue between its holes. The thread must have a SphereCollisionModel and a needle must carry
// it (refused otherwise).
//
// Puncture. A needle's tip that enters a lip from outside presses on it: the skin resists with
// F = k_i δ, δ the tip's depth past the point e where it entered, along the entered face's inward
// normal (k_i: "indentation_stiffness", N/m). Once F reaches the puncture force the skin gives
// way and e becomes a hole (entry). A tip that leaves the lip it went into makes a hole where it
// leaves (exit; the skin is not resisting from inside). A tip drawn back before puncturing makes
// nothing; one drawn back out through the face it went in by, within engage_distance of where it
// went in, leaves both holes withdrawn (they never hold the thread). Crossings are found by
// bisection on the segment between the tip's positions at consecutive steps: the tip is followed
// once per step, so a step in which it moves farther than the wound's gap may skip a face.
//
// Holes. A hole is fixed in its lip: X(t) = P_k(s_h, t) + o, o = e − P_k(s_h) at the puncture (it
// translates with the edge; its turn is neglected, point_target.hpp). The needle runs along its own
// arc through the holes it made. A hole whose angle in the needle's plane (from the swage towards
// the tip, unwrapped about the arc's middle) falls from within the arc to below −kEngageLag / R
// between two steps — the swage is kEngageLag past it — has the thread swaged to that needle
// running through it, if it lies within engage_distance of the needle's circle (radially and out
// of its plane; else the needle left its curve, and the hole holds nothing): the thread's point nearest to X within 5 mm of the
// swage, if it is within engage_distance (else the hole holds nothing, and says so), is where a
// sliding point (constraints/sliding_point_constraint.hpp) engages: s(t) starts at that abscissa
// and ṡ at the thread's sliding rate through the hole, tᵀ(Ẋ − Ṗ(s)) / |t|². From then on the thread
// slides through the hole with viscous friction η ("friction", N·s/m) and the hole's reaction
// pulls the lip. The sliding points are made when the scene is built, holes_per_lip per lip,
// inactive until engaged (their abscissas are DOFs of the state, sized once); a thread slid out of
// its hole releases it, and the slot stays used.
//
// Stitches (the metrics, "targets"): a stitch runs from a hole into the skin to the next hole out
// of the skin of the other lip, both by one needle. Its bites are the holes' distances from their
// cut faces (u at the puncture), its depth the deepest the tip went (v) between them, its angle
// that of the line between its two holes, in the skin's plane, to the wound's edge (90°: square
// across the wound), and each hole's distance to the nearest of the "targets" marked on the skin.
//
// The wound's state (holes, slots engaged, tips) lives outside SceneState, as the instruments'
// does: restoring an earlier state does not rewind it. What is not modelled (yet): the lip's dent
// under a pressing tip (the force is reported, the lip does not move under it), the needle's drag
// in the tissue and its contact with the skin, the skin's push on the thread loading the lips (the
// pad is kinematic: only the holes pull the lips), the exemption of the thread in the tissue from
// the lips' edge spheres (a bite must be deeper than the edge's radius).
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
    std::vector<Vec3> targets;        // marked entry and exit points on the skin (m)
  };
  static constexpr int kMaxHolesPerLip = 64;
  static constexpr int kMaxTargets = 1000;
  /// How far past a hole the swage goes before the thread engages it (m): half the length the
  /// swage clamps along the needle's axis (Needle::kSwageLead), where the thread follows the track.
  static constexpr double kEngageLag = 0.5 * Needle::kSwageLead;

  /// The "wound" block; throws SceneError at the faulty field (a lip or thread that is not a
  /// curve body of `scene`, a lip named twice or as the thread).
  static Settings settingsFromParams(const Params& p, const Scene& scene);

  explicit Wound(Settings settings);
  const Settings& settings() const { return settings_; }

  /// Adds the sliding points (inactive) to the thread's node and the pad to the root; the caller
  /// binds the scene again. `origin`: the JSON place of the block, for messages.
  void attach(Scene& scene, const std::string& origin);
  /// After the scene is bound: the lips' sides (ô away from the other lip) at the start, which
  /// needles carry the thread. Throws SceneError when the skin's normal runs along a lip, when
  /// the thread has no SphereCollisionModel (or the scene no collision pipeline: a factory without
  /// a default one), or no needle carries the thread.
  void bind(const Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles);
  /// The skin as an obstacle of the thread (added to the scene's root by attach).
  const WoundPad& pad() const { return *pad_; }

  /// Follows each needle's tip at the scene's state (the step's start): presses, punctures and
  /// exits; engages sliding points where the thread has passed a hole. Returns one line per event
  /// (without its time).
  std::vector<std::string> follow(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles);

  enum class Face { kSkin, kCut, kBottom, kFar };
  struct Hole {
    int lip = 0;
    double lip_abscissa = 0.0;    // s_h on the lip's edge
    Vec3 offset = Vec3::Zero();   // o (m)
    bool entry = true;            // made going in (else coming out)
    Face face = Face::kSkin;      // the face it is on
    double time = 0.0;            // s, when the needle made it
    int needle = 0;
    double from_edge = 0.0;       // u at the puncture (m): the distance from the cut face
    double depth = 0.0;           // an exit: the deepest v the tip reached since it went in (m)
    double target_distance = -1.0;  // to the nearest marked target (m); −1: no targets
    Vec3 made_at = Vec3::Zero();  // where it was made (m)
    Vec3 edge_tangent = Vec3::UnitX();  // its lip's edge tangent there
    Vec3 skin_normal = Vec3::UnitZ();   // the skin's normal there, ⊥ edge_tangent
    double angle = 0.0;           // its angle in its needle's plane at the last step (rad, unwrapped
                                  // about the arc's middle: 0 at the swage, α at the tip)
    int slot = kPending;          // its sliding point (index into slots), or a state below
  };
  static constexpr int kPending = -1;     // not reached by the swage yet
  static constexpr int kMissed = -2;      // the swage passed it, the thread was too far from it
  static constexpr int kNoSlot = -3;      // no sliding point was free
  static constexpr int kWithdrawn = -4;   // the tip was drawn back out where it went in
  const std::vector<Hole>& holes() const { return holes_; }
  /// X(t) of hole h at state s (m).
  Vec3 holePosition(const SceneState& s, const Hole& h) const;
  /// The sliding points, lip by lip (holes_per_lip each).
  const std::vector<constraints::SlidingPointConstraint*>& slots() const { return slots_; }

  /// The largest force the skin pushes back on a pressing needle's tip at the last step (N, 0 when
  /// none presses).
  double pressingForce() const;
  /// The largest of them so far (N).
  double peakForce() const { return peak_force_; }
  /// How many sliding points hold the thread now (engaged, not slid out).
  int holdingHoles() const;
  /// After a step: the gap's smallest and last values; one line per hole the thread slid out of.
  std::vector<std::string> afterStep(const SceneState& s);

  struct Stitch {
    int entry = 0, exit = 0;  // indices into holes()
    double entry_bite = 0.0, exit_bite = 0.0;  // m, from the cut faces
    double depth = 0.0;       // m
    double angle = 0.0;       // rad, to the wound's edge (π/2: square across)
  };
  std::vector<Stitch> stitches() const;
  /// metrics.json's "wound": the holes (lip, entry or exit, face, time, distance from the cut
  /// face, to the nearest target, whether it held the thread and holds it now), the stitches, how
  /// many holes hold the thread, the peak force on a pressing tip (N) and the gap at the start,
  /// its smallest and its last (m).
  nlohmann::json summary() const;
  /// One line for the log: holes, stitches with their bites, depth and angle, gap, peak force.
  std::string text() const;

  /// Lip k's edge at abscissa s at state s: P, t̂, n̂ (the skin's normal made ⊥ t̂), ô = ± n̂ × t̂
  /// away from the other lip, and Ṗ.
  WoundPad::Station edgeAt(const SceneState& s, int lip, double abscissa) const;
  /// Lip k at state s: whether x lies in it, and its local coordinates.
  struct LipPoint {
    bool inside = false;
    double s = 0.0;       // closest abscissa on the edge
    double across = 0.0;  // u = (x − P)·ô + r_e (m)
    double depth = 0.0;   // v = −(x − P)·n̂ + r_e (m)
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
    Face face = Face::kSkin;      // the face it entered by
    double force = 0.0;     // N
    double deepest = 0.0;   // the largest v since it went into in_lip (m)
    int entry_hole = -1;    // the hole it went into in_lip by
  };
  /// The point between a (in lip k: `inside_a`) and b (the other way) on the lip's boundary.
  Vec3 crossing(const SceneState& s, int lip, Vec3 a, Vec3 b, bool inside_a) const;
  /// The face of lip k nearest to x (in it or on it), and its inward normal.
  Face nearestFace(const LipPoint& l, Vec3* inward) const;
  int makeHole(const SceneState& s, int lip, const Vec3& at, bool entry, Face face, int needle, double depth,
               std::vector<std::string>& events);
  /// Whether hole h lies on the needle's circle (within engage_distance, radially and out of its plane).
  bool onNeedleTrack(const SceneState& s, const Hole& h, const Needle& needle) const;
  /// Whether hole h lies on the needle's track ahead of its swage: on its circle, its angle between
  /// −kEngageLag / R and α.
  bool aheadOfSwage(const SceneState& s, const Hole& h, const Needle& needle) const;
  /// The angle of x in the needle's plane from the swage towards the tip, in [α/2 − π, α/2 + π].
  static double angleOnNeedle(const Vec3& x, const Needle& needle);
  /// The pad where the lips are at state s, and the thread's spans in the tissue.
  void updatePad(const SceneState& s, const std::vector<std::unique_ptr<Needle>>& needles);
  void engage(Scene& scene, const std::vector<std::unique_ptr<Needle>>& needles, std::vector<std::string>& events);
  /// The thread's abscissa nearest to X within 5 mm of the needle's swage.
  double threadAtHole(const SceneState& s, const Needle& needle, const Vec3& X) const;

  Settings settings_;
  std::string origin_;
  const CurveBody* lips_[2] = {nullptr, nullptr};
  const CurveBody* thread_ = nullptr;
  double side_[2] = {1.0, 1.0};
  std::vector<char> carries_;   // per needle: it carries the wound's thread
  std::vector<constraints::SlidingPointConstraint*> slots_;
  std::vector<char> slot_used_;  // 0 free, 1 holding, 2 let go
  std::vector<Hole> holes_;
  std::vector<Tip> tips_;
  WoundPad* pad_ = nullptr;  // owned by the scene's root node
  std::vector<WoundPad::Station> edges_[2];             // the pad's edges, sized once
  std::vector<std::pair<double, double>> spans_;        // the thread's passage, grown once
  double peak_force_ = 0.0;
  double gap_start_ = 0.0, gap_min_ = 0.0, gap_last_ = 0.0;
};

}  // namespace filum::haptics
