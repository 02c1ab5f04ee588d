#include "filum/geometry/closest_point.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "filum/geometry/spline_curve.hpp"

namespace filum::geometry {

namespace {

struct Candidate {
  double s;
  double squared_distance;
};

/// Newton on g(s) = (P − x)·P' inside [lo, hi] from s0, bisection as safeguard; returns the best
/// of the refined point and the bracket ends.
Candidate refine(const CurveBasis& basis, ConstPointsRef q, const Vec3& x, double lo, double hi, double s0) {
  BasisRow row;
  auto squaredDistance = [&](double s) {
    basis.evaluate(s, row);
    return (curvePoint(row, q) - x).squaredNorm();
  };
  auto g = [&](double s, double* dg) {
    basis.evaluate(s, row);
    const CurveDerivatives c = curveDerivatives(row, q);
    const Vec3 r = c.point - x;
    if (dg) *dg = c.first.squaredNorm() + r.dot(c.second);
    return r.dot(c.first);
  };
  Candidate best{s0, squaredDistance(s0)};
  for (double end : {lo, hi}) {
    const double de = squaredDistance(end);
    if (de < best.squared_distance) best = {end, de};
  }

  // s0 is a discrete minimum, so a minimum of the distance lies in [lo, s0] if g changes sign
  // there from − to +, or in [s0, hi] likewise (the bracket may also hold a maximum and another
  // minimum, so both halves are tried).
  const double g_lo = g(lo, nullptr), g_0 = g(s0, nullptr), g_hi = g(hi, nullptr);
  const std::pair<double, double> halves[2] = {{lo, s0}, {s0, hi}};
  const bool sign_change[2] = {g_lo < 0.0 && g_0 > 0.0, g_0 < 0.0 && g_hi > 0.0};
  for (int h = 0; h < 2; ++h) {
    if (!sign_change[h]) continue;
    double a = halves[h].first, b = halves[h].second, s = 0.5 * (a + b);
    for (int iteration = 0; iteration < 60; ++iteration) {
      double dg = 0.0;
      const double gs = g(s, &dg);
      if (gs == 0.0) break;
      if (gs < 0.0) a = s; else b = s;
      double next = dg > 0.0 ? s - gs / dg : 0.5 * (a + b);
      if (!(next > a && next < b)) next = 0.5 * (a + b);  // Newton left the bracket: bisect
      const bool converged = std::abs(next - s) <= 4.0 * std::numeric_limits<double>::epsilon();
      s = next;
      if (converged || !(b > a)) break;
    }
    const double ds = squaredDistance(s);
    if (ds < best.squared_distance) best = {s, ds};
  }
  return best;
}

}  // namespace

ClosestPoint closestPoint(const CurveBasis& basis, ConstPointsRef q, const Vec3& x, int samples_per_piece) {
  if (q.rows() != basis.controlPointCount())
    throw std::invalid_argument("closestPoint: the basis has " + std::to_string(basis.controlPointCount()) +
                                " control points but q has " + std::to_string(q.rows()) + " rows");
  if (samples_per_piece < 1)
    throw std::invalid_argument("closestPoint: samples_per_piece must be >= 1, got " +
                                std::to_string(samples_per_piece));
  if (!x.allFinite()) throw std::invalid_argument("closestPoint: the query point is not finite");

  // Global search, piece by piece: distances at samples_per_piece + 1 abscissas of each piece.
  // On a curve that may be discontinuous (continuity() < 0: a knot of multiplicity d + 1) inner
  // piece ends are sampled kEndInset inside the piece, so that both one-sided limits are seen.
  const double kEndInset = basis.continuity() < 0 ? 1e-12 : 0.0;
  const std::vector<double> pieces = basis.breakpoints();
  std::vector<double> s(static_cast<std::size_t>(samples_per_piece) + 1), d(s.size());
  BasisRow row;
  Candidate best{0.0, std::numeric_limits<double>::infinity()};
  for (std::size_t p = 0; p + 1 < pieces.size(); ++p) {
    const double a = pieces[p], b = pieces[p + 1];
    const double inset = std::min(kEndInset, 0.25 * (b - a) / samples_per_piece);
    for (int j = 0; j <= samples_per_piece; ++j) {
      s[j] = a + (b - a) * j / samples_per_piece;
      if (j == 0 && p > 0) s[j] = a + inset;
      if (j == samples_per_piece) s[j] = p + 2 < pieces.size() ? b - inset : 1.0;
      basis.evaluate(s[j], row);
      d[j] = (curvePoint(row, q) - x).squaredNorm();
    }
    // Refine every discrete local minimum of the piece in its bracket.
    const int last = samples_per_piece;
    for (int k = 0; k <= last; ++k) {
      const bool left_ok = k == 0 || d[k] <= d[k - 1];
      const bool right_ok = k == last || d[k] <= d[k + 1];
      if (!left_ok || !right_ok) continue;
      const Candidate c = refine(basis, q, x, s[k == 0 ? 0 : k - 1], s[k == last ? last : k + 1], s[k]);
      if (c.squared_distance < best.squared_distance) best = c;
    }
  }
  basis.evaluate(best.s, row);
  ClosestPoint out;
  out.s = best.s;
  out.point = curvePoint(row, q);
  out.distance = (out.point - x).norm();
  return out;
}

}  // namespace filum::geometry
