#include "filum/visual/sphere_mesh.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace filum::visual {

TriangleMesh unitSphere(int rings) {
  if (rings < 2) throw std::invalid_argument("unitSphere: need at least 2 rings, got " + std::to_string(rings));
  const int around = 2 * rings;
  const int inner = rings - 1;  // latitude rings between the poles
  TriangleMesh m;
  m.vertices.resize(inner * around + 2, 3);
  // Vertex 0: south pole; rings from south to north; last: north pole.
  m.vertices.row(0) << 0.0, 0.0, -1.0;
  for (int i = 0; i < inner; ++i) {
    const double phi = -0.5 * std::numbers::pi + std::numbers::pi * (i + 1) / rings;  // latitude
    for (int j = 0; j < around; ++j) {
      const double theta = 2.0 * std::numbers::pi * j / around;
      m.vertices.row(1 + i * around + j) << std::cos(phi) * std::cos(theta), std::cos(phi) * std::sin(theta),
          std::sin(phi);
    }
  }
  const int north = inner * around + 1;
  m.vertices.row(north) << 0.0, 0.0, 1.0;
  m.normals = m.vertices;
  // Counter-clockwise seen from outside: going north (+φ) and east (+θ), east × north = outward.
  std::vector<Eigen::Vector3i> t;
  const auto at = [&](int ring, int j) { return 1 + ring * around + (j % around); };
  for (int j = 0; j < around; ++j) t.emplace_back(0, at(0, j + 1), at(0, j));
  for (int i = 0; i + 1 < inner; ++i)
    for (int j = 0; j < around; ++j) {
      t.emplace_back(at(i, j), at(i, j + 1), at(i + 1, j));
      t.emplace_back(at(i, j + 1), at(i + 1, j + 1), at(i + 1, j));
    }
  for (int j = 0; j < around; ++j) t.emplace_back(at(inner - 1, j), at(inner - 1, j + 1), north);
  m.triangles.resize(static_cast<Eigen::Index>(t.size()), 3);
  for (std::size_t f = 0; f < t.size(); ++f) m.triangles.row(static_cast<Eigen::Index>(f)) = t[f].transpose();
  return m;
}

void appendSphere(const TriangleMesh& unit, const Vec3& center, double radius, TriangleMesh& out) {
  const Eigen::Index v0 = out.vertices.rows(), f0 = out.triangles.rows();
  out.vertices.conservativeResize(v0 + unit.vertices.rows(), 3);
  out.normals.conservativeResize(v0 + unit.vertices.rows(), 3);
  out.triangles.conservativeResize(f0 + unit.triangles.rows(), 3);
  out.vertices.bottomRows(unit.vertices.rows()) = (radius * unit.vertices).rowwise() + center.transpose();
  out.normals.bottomRows(unit.vertices.rows()) = unit.normals;
  out.triangles.bottomRows(unit.triangles.rows()) = unit.triangles.array() + static_cast<int>(v0);
}

namespace {

/// sphereSet's loop, with sphere i's radius radius_of(i).
template <typename RadiusOf>
void buildSphereSet(const TriangleMesh& unit, const Points& centers, RadiusOf radius_of, TriangleMesh& out) {
  const Eigen::Index k = centers.rows(), nv = unit.vertices.rows(), nf = unit.triangles.rows();
  out.vertices.resize(k * nv, 3);
  out.normals.resize(k * nv, 3);
  out.triangles.resize(k * nf, 3);
  for (Eigen::Index i = 0; i < k; ++i) {
    out.vertices.middleRows(i * nv, nv) = (radius_of(i) * unit.vertices).rowwise() + centers.row(i);
    out.normals.middleRows(i * nv, nv) = unit.normals;
    out.triangles.middleRows(i * nf, nf) = unit.triangles.array() + static_cast<int>(i * nv);
  }
}

}  // namespace

void sphereSet(const TriangleMesh& unit, const Points& centers, double radius, TriangleMesh& out) {
  buildSphereSet(unit, centers, [radius](Eigen::Index) { return radius; }, out);
}

void sphereSet(const TriangleMesh& unit, const Points& centers, const VecX& radii, TriangleMesh& out) {
  if (radii.size() != centers.rows())
    throw std::invalid_argument("sphereSet: " + std::to_string(radii.size()) + " radii for " +
                                std::to_string(centers.rows()) + " centres");
  buildSphereSet(unit, centers, [&radii](Eigen::Index i) { return radii[i]; }, out);
}

}  // namespace filum::visual
