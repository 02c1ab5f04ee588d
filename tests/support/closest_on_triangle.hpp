// References for triangle-mesh queries, computed apart from CGAL: the exact distance of a point to
// a mesh (every triangle's closest point in closed form) and the winding number of a closed mesh
// around a point (the inside test's and the pseudo-normals' reference).
#pragma once

#include <algorithm>
#include <cmath>
#include <array>
#include <limits>
#include <vector>

#include "filum/core/types.hpp"

namespace filum::test {

/// Closest point of triangle abc to p (Ericson, Real-Time Collision Detection, §5.1.5): the
/// Voronoi regions of the vertices, edges and face, in exact closed form.
inline Vec3 closestOnTriangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1.0 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Distance of p to the mesh (vertices V × 3, triangles by index): the nearest of every
/// triangle's exact closest point.
inline double exactDistance(const Points& vertices, const std::vector<std::array<int, 3>>& triangles, const Vec3& p) {
  double best = std::numeric_limits<double>::infinity();
  for (const auto& t : triangles)
    best = std::min(best, (p - closestOnTriangle(p, vertices.row(t[0]).transpose(), vertices.row(t[1]).transpose(),
                                                 vertices.row(t[2]).transpose()))
                              .norm());
  return best;
}

/// Winding number of a closed mesh around p: Σ solid angles / 4π (Van Oosterom & Strackee 1983):
/// 1 inside, 0 outside, up to round-off.
inline double windingNumber(const Points& vertices, const std::vector<std::array<int, 3>>& triangles, const Vec3& p) {
  double sum = 0.0;
  for (const auto& t : triangles) {
    const Vec3 a = vertices.row(t[0]).transpose() - p, b = vertices.row(t[1]).transpose() - p,
               c = vertices.row(t[2]).transpose() - p;
    const double la = a.norm(), lb = b.norm(), lc = c.norm();
    sum += 2.0 * std::atan2(a.dot(b.cross(c)), la * lb * lc + a.dot(b) * lc + a.dot(c) * lb + b.dot(c) * la);
  }
  return sum / (4.0 * M_PI);
}

}  // namespace filum::test
