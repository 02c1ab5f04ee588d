#include "filum/visual/generalized_cylinder.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

#include "filum/geometry/rotation_minimizing_frames.hpp"

namespace filum::visual {

GeneralizedCylinder::GeneralizedCylinder(int rings, int sides, CapStyle caps, int cap_rings)
    : rings_(rings), sides_(sides), cap_rings_(cap_rings > 0 ? cap_rings : std::max(2, sides / 4)), caps_(caps) {
  if (rings < 2 || sides < 3)
    throw std::invalid_argument("GeneralizedCylinder: need rings >= 2 and sides >= 3, got " + std::to_string(rings) +
                                " and " + std::to_string(sides));
  for (int j = 0; j < sides_; ++j) {
    const double theta = 2.0 * std::numbers::pi * j / sides_;
    cos_.push_back(std::cos(theta));
    sin_.push_back(std::sin(theta));
  }
  for (int c = 1; c < cap_rings_; ++c) {
    const double phi = 0.5 * std::numbers::pi * c / cap_rings_;
    cos_phi_.push_back(std::cos(phi));
    sin_phi_.push_back(std::sin(phi));
  }

  // Vertex layout: side rings, then each cap's rings and its pole (or centre).
  const int side_vertices = rings_ * sides_;
  const int cap_ring_count = caps_ == CapStyle::kRound ? cap_rings_ - 1 : 1;
  start_cap_ = side_vertices;
  start_pole_ = start_cap_ + cap_ring_count * sides_;
  end_cap_ = start_pole_ + 1;
  end_pole_ = end_cap_ + cap_ring_count * sides_;
  const int vertex_count = end_pole_ + 1;

  // Ring sequences running along +T; a pole is encoded as −1 − index.
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> side;
  for (int k = 0; k < rings_; ++k) side.push_back(sideVertex(k, 0));
  if (caps_ == CapStyle::kRound) {
    std::vector<int> all{-1 - start_pole_};
    for (int c = cap_ring_count - 1; c >= 0; --c) all.push_back(start_cap_ + c * sides_);  // from the pole inwards
    all.insert(all.end(), side.begin(), side.end());
    for (int c = 0; c < cap_ring_count; ++c) all.push_back(end_cap_ + c * sides_);
    all.push_back(-1 - end_pole_);
    stitch(all, triangles);
  } else {
    stitch(side, triangles);
    stitch({-1 - start_pole_, start_cap_}, triangles);
    stitch({end_cap_, -1 - end_pole_}, triangles);
  }
  mesh_.vertices.setZero(vertex_count, 3);
  mesh_.normals.setZero(vertex_count, 3);
  mesh_.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) mesh_.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
}

void GeneralizedCylinder::stitch(const std::vector<int>& sequence, std::vector<Eigen::Vector3i>& out) const {
  // Between ring A and the next ring B (both running along +T, same angular order): the
  // triangles (A_j, A_j+1, B_j) and (A_j+1, B_j+1, B_j); ∂v/∂θ × T is the outward normal, so
  // these are counter-clockwise seen from outside. A pole collapses one of the two.
  const auto at = [&](int ring, int j) { return ring < 0 ? -1 - ring : ring + (j % sides_); };
  for (std::size_t r = 0; r + 1 < sequence.size(); ++r) {
    const int a = sequence[r], b = sequence[r + 1];
    for (int j = 0; j < sides_; ++j) {
      if (a >= 0) out.emplace_back(at(a, j), at(a, j + 1), at(b, j));
      if (b >= 0) out.emplace_back(at(a, j + 1), at(b, j + 1), at(b, j));
    }
  }
}

void GeneralizedCylinder::writeCap(int first, int pole, const geometry::CurveFrame& frame, double radius,
                                   double direction) {
  // direction −1: start cap (outward −T), +1: end cap (outward +T).
  const Vec3 outward = direction * frame.tangent;
  if (caps_ == CapStyle::kRound) {
    // Hemisphere: ring c at latitude φ_c, x + r (cos φ d_j + sin φ outward), normal the unit
    // radius vector. Rings are stored from the side (c = 1) towards the pole.
    for (int c = 0; c + 1 < cap_rings_; ++c)
      for (int j = 0; j < sides_; ++j) {
        const Vec3 n = cos_phi_[c] * (cos_[j] * frame.normal + sin_[j] * frame.binormal) + sin_phi_[c] * outward;
        mesh_.vertices.row(first + c * sides_ + j) = (frame.origin + radius * n).transpose();
        mesh_.normals.row(first + c * sides_ + j) = n.transpose();
      }
    mesh_.vertices.row(pole) = (frame.origin + radius * outward).transpose();
  } else {
    // Disk: the rim duplicates the end ring with the flat normal.
    for (int j = 0; j < sides_; ++j) {
      const Vec3 d = cos_[j] * frame.normal + sin_[j] * frame.binormal;
      mesh_.vertices.row(first + j) = (frame.origin + radius * d).transpose();
      mesh_.normals.row(first + j) = outward.transpose();
    }
    mesh_.vertices.row(pole) = frame.origin.transpose();
  }
  mesh_.normals.row(pole) = outward.transpose();
}

void GeneralizedCylinder::update(ConstPointsRef axis, ConstPointsRef unit_tangents, ConstPointsRef curvatures,
                                 const VecX& radii, const VecX& radius_slopes, const Vec3& initial_normal) {
  if (axis.rows() != rings_ || unit_tangents.rows() != rings_ || radii.size() != rings_ ||
      radius_slopes.size() != rings_ || (curvatures.rows() != 0 && curvatures.rows() != rings_))
    throw std::invalid_argument("GeneralizedCylinder::update: expected " + std::to_string(rings_) +
                                " axis points, tangents, radii and slopes");
  // Rotation-minimizing frames along the samples (O(rings)).
  frames_ = geometry::rotationMinimizingFrames(axis, unit_tangents, initial_normal);
  // Side rings: v = x + r d, n = normalize((1 − r d·κ) d − r' T).
  const bool curved = curvatures.rows() == rings_;
  for (int k = 0; k < rings_; ++k) {
    const geometry::CurveFrame& f = frames_[k];
    const double r = radii[k], slope = radius_slopes[k];
    const Vec3 kappa = curved ? Vec3(curvatures.row(k).transpose()) : Vec3::Zero();
    for (int j = 0; j < sides_; ++j) {
      const Vec3 d = cos_[j] * f.normal + sin_[j] * f.binormal;
      const double stretch = std::max(0.1, 1.0 - r * d.dot(kappa));
      mesh_.vertices.row(sideVertex(k, j)) = (f.origin + r * d).transpose();
      // |w d − r' T| = sqrt(w² + r'²) since d ⊥ T.
      mesh_.normals.row(sideVertex(k, j)) =
          ((stretch * d - slope * f.tangent) / std::sqrt(stretch * stretch + slope * slope)).transpose();
    }
  }
  writeCap(start_cap_, start_pole_, frames_.front(), radii[0], -1.0);
  writeCap(end_cap_, end_pole_, frames_.back(), radii[rings_ - 1], +1.0);
}

}  // namespace filum::visual
