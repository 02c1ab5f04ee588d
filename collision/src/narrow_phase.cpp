#include "filum/collision/narrow_phase.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "filum/collision/segment_closest_points.hpp"
#include "filum/core/growing_vector.hpp"

namespace filum::collision {

namespace {

Vec3 center(const SphereCollisionModel& m, int k) { return m.centers().row(k).transpose(); }
double speed(const SphereCollisionModel& m, int k) { return m.velocities().row(k).norm(); }

/// Whether the closest point at parameter u of chord k of m (against the chord [q0, q1]) is
/// the one that represents it: inside the chord, or at a vertex that is the closest point of
/// both chords sharing it, reported by the chord that starts there (or at a strand's ends).
bool representsClosestPoint(const SphereCollisionModel& m, int k, double u, const Vec3& q0, const Vec3& q1) {
  if (u > 0.0 && u < 1.0) return true;
  if (u >= 1.0) return !m.mapping().joinsNext(k + 1);  // an inner end vertex belongs to the next chord
  if (k == 0 || !m.mapping().joinsNext(k - 1)) return true;  // a strand's first point
  // u = 0: vertex k; keep it if chord k − 1 also has its closest point there (u' = 1).
  return closestPointsOnSegments(center(m, k - 1), center(m, k), q0, q1).s >= 1.0;
}

/// Keeps the first and the last of each run of consecutive contacts of out[first..] that
/// sameRun(out[k], out[j]) joins to the run's first one.
template <class SameRun>
void keepRunEnds(ContactSet& out, std::size_t first, SameRun sameRun) {
  std::size_t write = first;
  for (std::size_t k = first; k < out.size();) {
    std::size_t end = k + 1;  // [k, end): one run
    while (end < out.size() && sameRun(out[k], out[end])) ++end;
    out[write++] = out[k];
    if (end - k >= 2) out[write++] = out[end - 1];
    k = end;
  }
  out.resize(write);
}

/// Whether two contacts may join one run of keepRunEnds: both on the same straight piece of A
/// and, unless against an obstacle, the same straight piece of B (rows of two control points).
bool onSamePieces(const Contact& x, const Contact& y) {
  const auto same = [](const PointWeights& p, const PointWeights& q) {
    return p.count == 2 && q.count == 2 && p.point[0] == q.point[0] && p.point[1] == q.point[1];
  };
  return same(x.a.weights(), y.a.weights()) && (x.againstObstacle() || same(x.b.weights(), y.b.weights()));
}

/// Whether two obstacle contacts are against one plane: their normals equal to round-off and
/// their surface points on one plane (a step or a plate of a mesh has parallel faces at other
/// heights, a bump's crest the normal of the troughs beside it). To 1e-9 of the radius: two
/// closest points of one face differ along n by the round-off of their coordinates, ε |x| ≈
/// 2e-16 m in a scene a metre across, far below 1e-9 r (1e-13 m for a 0.1 mm thread), while a
/// face of another height differs by what a contact can feel.
bool onePlane(const Contact& a, const Contact& b) {
  return a.normal.dot(b.normal) >= 1.0 - 1e-12 &&
         std::abs(a.normal.dot(a.surface_point - b.surface_point)) <= 1e-9 * std::max(a.radius, b.radius);
}

/// The vertex of the linear piece (two control points) contact x lies at: 0 or 1 (its first or
/// second point, the other's weight zero), or −1 inside the piece or on another kind of point.
int vertexOfPiece(const Contact& x) {
  const PointWeights& w = x.a.weights();
  if (w.count != 2) return -1;
  if (w.weight[1] == 0.0) return 0;
  if (w.weight[0] == 0.0) return 1;
  return -1;
}

/// The control point at vertex v (0, 1) of x's piece.
int vertexPoint(const Contact& x, int v) { return x.a.weights().point[v]; }

/// Whether contact y sits at control point p (a vertex of its own piece) against x's plane.
bool atVertex(const Contact& y, int p, const Contact& x) {
  const int v = vertexOfPiece(y);
  return v >= 0 && vertexPoint(y, v) == p && onePlane(x, y);
}

/// Fewer rows where they would be redundant: of consecutive contacts out[first..] with one linear
/// piece of the curve (degree 1: a rod's segment, two control points) and one plane (onePlane: a
/// flat obstacle face there), keeps the first and the last. Exact: on a straight piece against a
/// plane the gap n·P(s) − d − r is linear in s, so the spheres between two contacts cannot come
/// closer than the nearer of them, and their rows n · (b_0 x_i + b_1 x_{i+1}) are combinations of
/// the two kept ones — rows that only made the contact solve's matrix larger and singular (a rod
/// lying on a table had ~7 spheres per 10 mm segment: 3.5 times the rows). Curved pieces (splines
/// of degree >= 2) and curved surfaces (normals that differ) keep every contact.
void keepSpanEnds(ContactSet& out, std::size_t first) {
  keepRunEnds(out, first, [](const Contact& a, const Contact& b) { return onSamePieces(a, b) && onePlane(a, b); });
  // Then a contact inside a piece goes too when both vertices of its piece have their own
  // contact against the same plane (the neighbours in sphere order: the vertex before it ends or
  // starts the run, the vertex after it starts the next piece's run). The gap is linear along
  // the piece, so its smallest value is at a vertex: the vertex rows hold the whole piece. A rod's
  // vertices are sphere centres (SphereSamplingMapping places a polyline's centres piece by
  // piece), so a rod lying on a face has one contact per vertex instead of two per piece.
  std::size_t write = first;
  for (std::size_t k = first; k < out.size(); ++k) {
    const Contact& x = out[k];
    const PointWeights& w = x.a.weights();
    const bool inside = w.count == 2 && w.weight[0] != 0.0 && w.weight[1] != 0.0;
    if (inside && x.againstObstacle() && k > first && k + 1 < out.size() && atVertex(out[k - 1], w.point[0], x) &&
        atVertex(out[k + 1], w.point[1], x))
      continue;
    out[write++] = x;
  }
  out.resize(write);
}

}  // namespace

void findObstacleContacts(const SphereCollisionModel& model, int model_index, const Obstacle& obstacle,
                          int obstacle_index, const NarrowPhaseSettings& settings, ContactSet& out) {
  const double mu = obstacle.friction().value_or(settings.friction);
  const double surface_speed = obstacle.speed();
  const std::size_t first = out.size();
  SurfaceSample sample;
  for (int k = 0; k < model.sphereCount(); ++k) {
    // Reach of the sphere during the step: d − r <= margin + (|v_k| + u) h.
    const double reach = settings.margin + (speed(model, k) + surface_speed) * settings.time_step;
    const double r = model.radius(k);
    if (obstacle.passesThrough(model.curve(), model.mapping().abscissas()[k])) continue;
    if (!obstacle.sample(center(model, k), r + reach, sample)) continue;
    if (sample.distance - r > reach) continue;
    Contact c;
    c.model_a = model_index;
    c.a = model.mapping().chordPoint(model.curve(), k, 0.0);  // centre k
    c.obstacle = obstacle_index;
    c.surface_point = sample.point;
    c.surface_velocity = sample.velocity;
    c.time = settings.time;
    c.normal = sample.normal;
    c.radius = r;
    c.friction = mu;
    out.push_back(c);
  }
  keepSpanEnds(out, first);
}

bool findChordContact(const SphereCollisionModel& a, int model_a, int k, const SphereCollisionModel& b, int model_b,
                      int l, const NarrowPhaseSettings& settings, ContactSet& out) {
  const bool self = model_a == model_b;
  if (self && a.mapping().strandOf(k) == a.mapping().strandOf(l) && std::abs(k - l) <= 1)
    return false;  // neighbouring chords share a sphere
  const Vec3 p0 = center(a, k), p1 = center(a, k + 1), q0 = center(b, l), q1 = center(b, l + 1);
  const SegmentClosestPoints cp = closestPointsOnSegments(p0, p1, q0, q1);

  // Continuous detection: the gap can shrink by at most the largest relative speed times h; with
  // each chord's larger radius, since the closest points may move along a tapered chord within
  // the step.
  const double sweep = (std::max(speed(a, k), speed(a, k + 1)) + std::max(speed(b, l), speed(b, l + 1))) *
                       settings.time_step;
  if (cp.distance - (a.chordRadius(k) + b.chordRadius(l)) > settings.margin + sweep) return false;

  // One contact per touching point (vertices shared by two chords).
  if (!representsClosestPoint(a, k, cp.s, q0, q1)) return false;
  if (!representsClosestPoint(b, l, cp.t, p0, p1)) return false;

  // Self-collision: skip points closer than the exclusion distance along the curve.
  if (self && a.mapping().arcDistance(k, cp.s, l, cp.t) < a.exclusion(k, l)) return false;

  Contact c;
  c.model_a = model_a;
  c.a = a.mapping().chordPoint(a.curve(), k, cp.s);
  c.model_b = model_b;
  c.b = b.mapping().chordPoint(b.curve(), l, cp.t);
  c.time = settings.time;
  c.radius = a.chordRadius(k, cp.s) + b.chordRadius(l, cp.t);  // the radii at the closest points
  c.friction = settings.friction;
  // n = (p − q)/|p − q|; centre lines already touching: the common perpendicular, oriented from
  // B's chord midpoint towards A's.
  const double scale = (p1 - p0).norm() + (q1 - q0).norm();
  if (cp.distance > 1e-12 * scale) {
    c.normal = (cp.p - cp.q) / cp.distance;
  } else {
    Vec3 n = (p1 - p0).cross(q1 - q0);
    if (!(n.norm() > 0.0)) n = Vec3::UnitZ();
    n.normalize();
    if (n.dot(0.5 * (p0 + p1) - 0.5 * (q0 + q1)) < 0.0) n = -n;
    c.normal = n;
  }
  out.push_back(c);
  return true;
}

void AxisBounds::build(const Points& axis, int vertices) {
  const int chords = std::max(0, std::min(vertices, static_cast<int>(axis.rows())) - 1);
  blocks_ = (chords + kChords - 1) / kChords;
  resizeGrowing(spheres_, blocks_);
  for (int b = 0; b < blocks_; ++b) {
    const int first = b * kChords, last = std::min(first + kChords, chords);  // vertices first..last
    Vec3 low = axis.row(first).transpose(), high = low;
    for (int v = first + 1; v <= last; ++v) {
      low = low.cwiseMin(axis.row(v).transpose());
      high = high.cwiseMax(axis.row(v).transpose());
    }
    BoundingSphere& sphere = spheres_[b];
    sphere.center = 0.5 * (low + high);
    sphere.radius = 0.0;
    for (int v = first; v <= last; ++v)
      sphere.radius = std::max(sphere.radius, (axis.row(v).transpose() - sphere.center).norm());
  }
}

AxisPoint nearestAxisPoint(const Points& axis, const SphereSamplingMapping& sampling, const Vec3& x,
                           const AxisBounds* bounds, int hint) {
  AxisPoint best;
  double nearest = std::numeric_limits<double>::infinity();
  bool beyond_end = false;
  const int count = sampling.outputCount();
  // Chord l measured; kept when nearer than the best so far, or as near and earlier (the
  // brute-force scan's choice, whatever order the chords are measured in).
  auto measure = [&](int l) {
    if (!sampling.joinsNext(l)) return;  // a cut: no chord across it
    const Vec3 y0 = axis.row(l).transpose(), y1 = axis.row(l + 1).transpose(), e = y1 - y0;
    const double length2 = e.squaredNorm();
    const double t = length2 > 0.0 ? (x - y0).dot(e) / length2 : 0.0;
    const double u = std::clamp(t, 0.0, 1.0);
    const double d = (x - (y0 + u * e)).norm();
    if (d < nearest || (d == nearest && l < best.chord)) {
      nearest = d;
      best = {l, u, d};
      const bool first = l == 0 || !sampling.joinsNext(l - 1);
      const bool last = l + 2 >= count || !sampling.joinsNext(l + 1);
      beyond_end = (first && t < 0.0) || (last && t > 1.0);
    }
  };
  if (bounds == nullptr) {
    for (int l = 0; l + 1 < count; ++l) measure(l);
  } else {
    if (hint >= 0 && hint + 1 < count) measure(hint);
    for (int b = 0; b < bounds->blocks(); ++b) {
      // Every point of the block's chords is at least |x − c| − R from x. Skipped only when that
      // bound, less its round-off and that of the distances measured (a few ε of the
      // coordinates' size; 64 ε taken), still exceeds the nearest distance found.
      const BoundingSphere& block = bounds->block(b);
      const double to_center = (x - block.center).norm();
      const double slack =
          64.0 * std::numeric_limits<double>::epsilon() * (x.norm() + block.center.norm() + block.radius + to_center);
      if (to_center - block.radius - slack > nearest) continue;
      const int end = std::min((b + 1) * AxisBounds::kChords, count - 1);
      for (int l = b * AxisBounds::kChords; l < end; ++l) measure(l);
    }
  }
  if (beyond_end) {
    const Vec3 y0 = axis.row(best.chord).transpose(), y1 = axis.row(best.chord + 1).transpose();
    const Vec3 offset = x - y0, e = y1 - y0;
    const double length2 = e.squaredNorm();
    best.radial = length2 > 0.0 ? (offset - (offset.dot(e) / length2) * e).norm() : offset.norm();
    best.end_sphere = best.chord + (best.u > 0.5 ? 1 : 0);  // u is 0 or 1 there (clamped t)
    best.chord = -1;
  }
  return best;
}

TubePlace placeInTube(const AxisPoint& axis, const SphereCollisionModel& tube) {
  if (axis.chord >= 0)
    return axis.distance < 0.5 * (tube.lumenRadius(axis.chord, axis.u) + tube.chordRadius(axis.chord, axis.u))
               ? TubePlace::kInside
               : TubePlace::kOutside;
  // In the opening: the centre within the lumen's radius of the end chord's line (at most its
  // own radius into the rim, which the lumen's rows then push back in); farther out, the rim and
  // the outer surface are touched as usual.
  // (No end sphere when no chord was measured: a tube of one sphere, or non-finite positions.)
  const double lumen = axis.end_sphere >= 0 ? tube.lumenRadius(axis.end_sphere) : tube.lumenRadius();
  return axis.radial < lumen ? TubePlace::kOpening : TubePlace::kOutside;
}

void findLumenContacts(const SphereCollisionModel& inner, int model_inner, const SphereCollisionModel& tube,
                       int model_tube, double friction, const NarrowPhaseSettings& settings, ContactSet& out,
                       std::vector<TubePlace>& place, AxisBounds& bounds) {
  const std::size_t first = out.size();
  double tube_speed = 0.0;  // the largest speed of the tube's centre line
  for (int l = 0; l < tube.sphereCount(); ++l) tube_speed = std::max(tube_speed, speed(tube, l));
  place.assign(inner.sphereCount(), TubePlace::kOutside);  // within the capacity reserved at init
  bounds.build(tube.centers(), tube.sphereCount());
  int hint = -1;  // the last sphere's chord: its neighbour's is near
  for (int k = 0; k < inner.sphereCount(); ++k) {
    const Vec3 x = center(inner, k);
    const AxisPoint axis = nearestAxisPoint(tube.centers(), tube.mapping(), x, &bounds, hint);
    if (axis.chord >= 0) hint = axis.chord;
    place[k] = placeInTube(axis, tube);
    if (place[k] != TubePlace::kInside) continue;  // beyond the tube's ends, or beside it
    const double reach = settings.margin + (speed(inner, k) + tube_speed) * settings.time_step;
    const double clearance = tube.lumenRadius(axis.chord, axis.u) - inner.radius(k);  // R_in − r_k
    if (clearance - axis.distance > reach) continue;  // g = (R_in − r_k) − d
    const int l = axis.chord;
    const Vec3 y0 = center(tube, l), y1 = center(tube, l + 1);
    const Vec3 y = y0 + axis.u * (y1 - y0);
    Contact c;
    c.model_a = model_inner;
    c.a = inner.mapping().chordPoint(inner.curve(), k, 0.0);  // centre k
    c.model_b = model_tube;
    c.b = tube.mapping().chordPoint(tube.curve(), l, axis.u);
    c.time = settings.time;
    c.radius = -clearance;
    c.friction = friction;
    // n towards the axis from the wall the sphere is heading for: its offset from the axis
    // predicted at the step's end, p = (x + h v) − (y + h w) (w the axis point's velocity),
    // across the chord, p⊥ = p − (p·e) e, gives n = −p⊥/|p⊥|. At rest, or sliding along the
    // wall, that is the nearest wall point, n = (y − x)/d. A sphere crossing the lumen within the
    // step (a clearance of tens of µm is crossed in a millisecond at a few cm/s) gets the wall
    // it would hit: the row of the wall behind it would only stop it moving back. A sphere that
    // stays on the axis (p⊥ = 0: far from either wall, the contact only waits) takes any
    // direction across the chord.
    const Vec3 e = (y1 - y0).normalized();  // Eigen: zero for a zero chord (then at_vertex below)
    const Vec3 w = (1.0 - axis.u) * tube.velocities().row(l).transpose() + axis.u * tube.velocities().row(l + 1).transpose();
    const Vec3 predicted = (x - y) + settings.time_step * (inner.velocities().row(k).transpose() - w);
    // At a vertex of the axis (u = 0 or 1: the nearest point is a bend's corner) the offset is not
    // across the chord: it is taken whole.
    const bool at_vertex = axis.u <= 0.0 || axis.u >= 1.0 || e.squaredNorm() == 0.0;
    const Vec3 across = at_vertex ? predicted : Vec3(predicted - predicted.dot(e) * e);
    const double scale = (y1 - y0).norm() + inner.radius();
    c.normal = across.norm() > 1e-12 * scale ? Vec3(-across / across.norm())
                                              : Vec3(e.squaredNorm() > 0.0 ? e.unitOrthogonal() : Vec3::UnitZ());
    out.push_back(c);
  }
  keepRunEnds(out, first, onSamePieces);
}

}  // namespace filum::collision
