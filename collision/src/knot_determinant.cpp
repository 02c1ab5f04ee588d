#include "filum/collision/knot_determinant.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include "knot_diagram.hpp"

namespace filum::collision {

Points closeFarAway(const Points& open, double far) {
  const int m = static_cast<int>(open.rows());
  const Vec3 centroid = open.colwise().mean().transpose();
  double extent = 0.0;
  for (int i = 0; i < m; ++i) extent = std::max(extent, (open.row(i).transpose() - centroid).norm());
  const double radius = far * std::max(extent, 1e-12);
  auto outward = [&](const Vec3& p) {
    const Vec3 d = p - centroid;
    return d.norm() > 0.0 ? Vec3(d.normalized()) : Vec3::UnitX();
  };
  const Vec3 first = open.row(0).transpose(), last = open.row(m - 1).transpose();
  const Vec3 da = outward(last), db = outward(first);
  // Third point: between the two far ends, or perpendicular to them if they are opposite.
  Vec3 dc = da + db;
  if (dc.norm() < 1e-6) {
    dc = da.cross(Vec3::UnitX());
    if (dc.norm() < 1e-6) dc = da.cross(Vec3::UnitY());
  }
  dc.normalize();
  Points closed(m + 3, 3);
  closed.topRows(m) = open;
  closed.row(m) = (centroid + radius * da).transpose();
  closed.row(m + 1) = (centroid + radius * dc).transpose();
  closed.row(m + 2) = (centroid + radius * db).transpose();
  return closed;
}

namespace {

/// det of an integer matrix modulo the prime p (Gaussian elimination in Z/pZ), in (−p/2, p/2).
long determinantModulo(std::vector<std::vector<long>> a, long p) {
  const int n = static_cast<int>(a.size());
  auto power = [p](long b, long e) {
    long r = 1;
    b %= p;
    for (; e > 0; e >>= 1, b = b * b % p)
      if (e & 1) r = r * b % p;
    return r;
  };
  long det = 1;
  for (auto& row : a)
    for (long& x : row) x = ((x % p) + p) % p;
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    while (pivot < n && a[pivot][k] == 0) ++pivot;
    if (pivot == n) return 0;
    if (pivot != k) {
      std::swap(a[k], a[pivot]);
      det = (p - det) % p;
    }
    det = det * a[k][k] % p;
    const long inverse = power(a[k][k], p - 2);  // Fermat: a^(p−2) = a⁻¹ mod p
    for (int i = k + 1; i < n; ++i) {
      const long factor = a[i][k] * inverse % p;
      if (factor == 0) continue;
      for (int j = k; j < n; ++j) a[i][j] = ((a[i][j] - factor * a[k][j]) % p + p) % p;
    }
  }
  return det > p / 2 ? det - p : det;
}

/// |det| of an integer matrix, exact when |det| < 5e8: the residues modulo two primes near 1e9
/// agree only then (a knot determinant is a small integer: 3 for the trefoil).
long integerDeterminant(const std::vector<std::vector<long>>& a) {
  if (a.empty()) return 1;
  const long d1 = determinantModulo(a, 1000000007L), d2 = determinantModulo(a, 998244353L);
  return d1 == d2 ? std::abs(d1) : -1;
}

}  // namespace

bool projectDiagram(const Points& closed, const Vec3& direction, std::vector<DiagramCrossing>& list) {
  list.clear();
  const int m = static_cast<int>(closed.rows());
  const Vec3 d = direction.normalized();
  // (u, w, d) right-handed: (x·u, x·w) are the coordinates seen from +d.
  const Vec3 u = d.unitOrthogonal(), w = d.cross(u);
  std::vector<Eigen::Vector2d> p(m);
  std::vector<double> h(m);
  for (int i = 0; i < m; ++i) {
    const Vec3 x = closed.row(i).transpose();
    p[i] = Eigen::Vector2d(x.dot(u), x.dot(w));
    h[i] = x.dot(d);
  }
  // Crossings of non-adjacent projected edges.
  for (int i = 0; i < m; ++i)
    for (int j = i + 2; j < m; ++j) {
      if (i == 0 && j == m - 1) continue;  // adjacent through the closing edge
      const Eigen::Vector2d a = p[i], b = p[(i + 1) % m], c = p[j], e = p[(j + 1) % m];
      const Eigen::Vector2d r = b - a, s = e - c;
      const double denom = r.x() * s.y() - r.y() * s.x();
      const double scale = r.norm() * s.norm();
      const Eigen::Vector2d ca = c - a;
      const double t = (ca.x() * s.y() - ca.y() * s.x());
      const double v = (ca.x() * r.y() - ca.y() * r.x());
      if (std::abs(denom) <= 1e-12 * scale) {
        // Parallel edges: a problem only if they overlap on one line.
        if (std::abs(ca.x() * r.y() - ca.y() * r.x()) <= 1e-12 * scale + 1e-300) {
          const double lo = std::min(ca.dot(r), (e - a).dot(r)), hi = std::max(ca.dot(r), (e - a).dot(r));
          if (hi >= 0.0 && lo <= r.squaredNorm()) return false;
        }
        continue;
      }
      const double ti = t / denom, tj = v / denom;
      if (ti < 0.0 || ti > 1.0 || tj < 0.0 || tj > 1.0) continue;
      // A crossing at (or within round-off of) a vertex: not generic.
      const double eps = 1e-9;
      if (ti < eps || ti > 1.0 - eps || tj < eps || tj > 1.0 - eps) return false;
      const double hi = h[i] + ti * (h[(i + 1) % m] - h[i]);
      const double hj = h[j] + tj * (h[(j + 1) % m] - h[j]);
      if (std::abs(hi - hj) <= 1e-14 * (std::abs(hi) + std::abs(hj))) return false;  // the strands meet
      // o × u with o the over strand's direction, u the under strand's: r × s or s × r.
      const double cross = hi > hj ? denom : -denom;
      const int sign = cross > 0.0 ? 1 : -1;
      if (hi > hj)
        list.push_back({i + ti, j + tj, sign});
      else
        list.push_back({j + tj, i + ti, sign});
    }
  return true;
}

long knotDeterminant(const Points& closed, const Vec3& direction, int* crossings) {
  std::vector<DiagramCrossing> list;
  if (!projectDiagram(closed, direction, list)) return -1;
  const int n = static_cast<int>(list.size());
  if (crossings) *crossings = n;
  if (n <= 2) return 1;  // a diagram with at most two crossings is the unknot
  // Under-crossings in order along the curve: arc k ends at under-crossing k.
  std::sort(list.begin(), list.end(), [](const DiagramCrossing& x, const DiagramCrossing& y) { return x.under < y.under; });
  auto arcOf = [&](double position) {
    // Arc k covers (under_{k−1}, under_k]; positions after the last under-crossing are on arc 0.
    for (int k = 0; k < n; ++k)
      if (position <= list[k].under) return k;
    return 0;
  };
  std::vector<std::vector<long>> matrix(n, std::vector<long>(n, 0));
  for (int k = 0; k < n; ++k) {
    // 2 x_over − x_in − x_out = 0 (in: arc k, out: arc k + 1)
    matrix[k][arcOf(list[k].over)] += 2;
    matrix[k][k] -= 1;
    matrix[k][(k + 1) % n] -= 1;
  }
  // Delete the last row and column.
  matrix.pop_back();
  for (auto& row : matrix) row.pop_back();
  return integerDeterminant(matrix);
}

long knotDeterminant(const Points& closed, int* crossings) {
  // Skew directions, none along an axis or a diagonal (generic for hand-built polygons).
  static const double kDirections[][3] = {{0.3137, 0.7288, 0.6087}, {-0.5471, 0.2269, 0.8056},
                                          {0.8169, -0.3946, 0.4207}, {0.1234, -0.9121, 0.3907},
                                          {-0.6633, -0.5218, 0.5366}, {0.4472, 0.1361, -0.8840}};
  for (const auto& dir : kDirections) {
    const long det = knotDeterminant(closed, Vec3(dir[0], dir[1], dir[2]), crossings);
    if (det >= 0) return det;
  }
  return -1;
}

}  // namespace filum::collision
