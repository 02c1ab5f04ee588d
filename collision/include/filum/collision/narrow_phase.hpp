// Narrow phase: from candidate pairs to the contacts of one step (contact.hpp), at the step's
// start state, with continuous detection over the step (docs/architecture.md, "One step":
// detectCollisions).
//
// Thread–obstacle, per sphere k of radius r at centre x_k moving at v_k, against an obstacle
// whose surface moves at most at speed u: the sphere may touch the surface within the step if
//   d(x_k) − r <= margin + (|v_k| + u) h       (h: the time step),
// since the distance between two moving sets decreases at most at their relative speed. Each
// such sphere gives a contact at its centre's abscissa, with the surface point and normal of
// the obstacle's query.
//
// Thread–thread, per pair of chords [x_k, x_{k+1}] of A and [y_l, y_{l+1}] of B (B may be A):
// closest points p = x_k + s (x_{k+1} − x_k), q = y_l + t (y_{l+1} − y_l) at the start, gap
// |p − q| − (r_A + r_B), and the same conservative continuous test with the largest endpoint
// speeds of both chords. The contact point is p on A (weights (1 − s) W_k + s W_{k+1}), q on B,
// normal n = (p − q)/|p − q|. So that one touching point gives one contact and not one per
// chord sharing it, a closest point at a chord's end vertex is kept only where that vertex is
// the closest point from both chords that share it (a convex corner), and then by the chord
// that starts there; closest points inside chords are always kept. On one thread, chords that
// are neighbours or closer than the exclusion distance along the curve are skipped
// (sphere_collision_model.hpp).
//
// Inside a tube (coaxial instruments: an instrument A of radius r running in the lumen of radius
// R_in of a tube B): each sphere x_k of A against the tube's centre line, the chords
// [y_l, y_{l+1}] of B; the nearest point y = y_l + u (y_{l+1} − y_l) at distance d. A sphere
// stays inside while d <= R_in − r, so the gap is
//   g = (R_in − r) − d = n·(x_A − x_B) − R   with   n = (y − x)/d   (towards the axis),
//                                                    R = −(R_in − r),
// (n from the wall the sphere is heading for: where its offset from the axis, moved on by its
// velocity relative to the tube's over the step, points; at rest the nearest wall point), the
// thread–thread contact of contact.hpp with a negative contact distance, and its rows, force
// (λ n on A, pushing it back towards the axis, −λ n on the tube's wall) and friction are those of
// every contact. Kept while g <= margin + (|v_k| + max |w_l|) h, as above. Only spheres inside
// the tube are held: a sphere whose nearest point is beyond a strand's end of the tube (t < 0 on
// its first chord, t > 1 on its last) is past the tip or behind the hub, and one farther from
// the axis than the middle of the wall lies beside the tube (a wire out of the tip and curled
// back); both meet the tube as any two threads meet (placeInTube), except that a sphere beyond
// an end in line with the lumen is going in or out through the opening and touches nothing of
// the tube. Of consecutive
// contacts between one straight piece of A (degree 1: a rod's segment) and one straight piece of
// B, only the first and the last are kept: the distance from a point moving along a line to
// another line is convex in the parameter, so d is largest, and g smallest, at the ends of the
// run, and the spheres in between cannot leave the lumen while those two are held.
#pragma once

#include <vector>

#include "filum/collision/contact.hpp"
#include "filum/collision/obstacle.hpp"
#include "filum/collision/sphere_collision_model.hpp"
#include "filum/collision/uniform_grid_broad_phase.hpp"

namespace filum::collision {

struct NarrowPhaseSettings {
  double margin = 0.0;            // m: contacts are kept up to this gap (beyond the sweep)
  double time_step = 0.0;         // h (s): the sweep of continuous detection; 0: discrete
  double friction = 0.0;          // μ of thread–thread contacts and obstacles without their own
  double time = 0.0;              // t_0 (s), the step's start
};

/// Appends to `out` the contacts of the spheres of `model` (index model_index) with `obstacle`.
void findObstacleContacts(const SphereCollisionModel& model, int model_index, const Obstacle& obstacle,
                          int obstacle_index, const NarrowPhaseSettings& settings, ContactSet& out);

/// Appends to `out` the contact between chord k of model a and chord l of model b, if any.
/// For a == b (self-collision) the caller passes k < l.
bool findChordContact(const SphereCollisionModel& a, int model_a, int k, const SphereCollisionModel& b, int model_b,
                      int l, const NarrowPhaseSettings& settings, ContactSet& out);

/// The nearest point of a tube's centre line (the chords between the centres `axis` of its
/// sampling) to x: chord l, parameter u in [0, 1], distance d; chord −1 when that point lies
/// beyond one of the tube's open ends (t < 0 on a strand's first chord, t > 1 on its last), and
/// then `radial`, the distance of x from that end chord's line extended, and `end_sphere`, the
/// tube's sphere at that end.
struct AxisPoint {
  int chord = -1;
  double u = 0.0;
  double distance = 0.0;
  double radial = 0.0;
  int end_sphere = -1;
};
/// Bounding spheres of a tube's centre line, kChords chords a block (each chord lies within the
/// sphere about its block's vertices): nearestAxisPoint skips a block that lies farther from x
/// than the nearest point already found, instead of measuring all n chords for every sphere.
class AxisBounds {
 public:
  static constexpr int kChords = 8;
  /// The blocks of the chords between the first `vertices` rows of `axis` (a model's centres
  /// are held in storage of its capacity; storage grows only).
  void build(const Points& axis, int vertices);
  int blocks() const { return blocks_; }
  const BoundingSphere& block(int b) const { return spheres_[b]; }

 private:
  int blocks_ = 0;
  std::vector<BoundingSphere> spheres_;
};
/// With `bounds` (built on the same axis) the blocks farther than the nearest point found are
/// skipped, chord `hint` (a neighbour's, or −1) measured first; the result is the same as without,
/// bit for bit: the nearest chord, the first of equally near ones.
AxisPoint nearestAxisPoint(const Points& axis, const SphereSamplingMapping& sampling, const Vec3& x,
                           const AxisBounds* bounds = nullptr, int hint = -1);

/// Where a sphere is with respect to a tube.
enum class TubePlace : char {
  kOutside,  // beside the tube, or away from its ends: meets the tube as any thread does
  kInside,   // within its length, nearer its axis than the middle of its wall: held by the lumen
  kOpening,  // beyond an end, within the lumen's radius of its axis extended (going in or out
             // through the opening): neither held nor touching the tube's end, open there
};
/// The place of a sphere whose nearest point of the tube's axis is `axis`: ½ (R_in + R_out), the
/// middle of the wall, separates in from out along the tube, R_in beyond its ends.
TubePlace placeInTube(const AxisPoint& axis, const SphereCollisionModel& tube);

/// Appends to `out` the contacts holding the spheres of `inner` that are inside `tube` in its
/// lumen (tube.narrowestLumen() > inner.radius()), with friction μ; place[k] is each sphere's
/// place (resized to inner's sphere count).
/// `bounds`: the workspace of the tube's AxisBounds.
void findLumenContacts(const SphereCollisionModel& inner, int model_inner, const SphereCollisionModel& tube,
                       int model_tube, double friction, const NarrowPhaseSettings& settings, ContactSet& out,
                       std::vector<TubePlace>& place, AxisBounds& bounds);

}  // namespace filum::collision
