// GeneralizedCylinder: the skin of a tube around a curve axis (the paper draws the thread as a
// generalized cylinder around its spline axis; Bloomenthal, "Calculation of reference frames
// along a space curve", Graphics Gems I, 1990). Around each axis sample x_k with unit tangent
// T_k, a ring of `sides` vertices
//   v_kj = x_k + r_k (cos θ_j N_k + sin θ_j B_k),   θ_j = 2π j / sides,
// where (T_k, N_k, B_k) are rotation-minimizing frames (geometry/rotation_minimizing_frames.hpp,
// double reflection): no twist about the tangent, so the quads do not shear as the thread bends.
// The radius r_k may vary along the axis (radius_profile.hpp). The smooth vertex normal is the
// exact normal of the swept surface x(ℓ, θ) = X(ℓ) + r(ℓ) d(ℓ, θ), d = cos θ N + sin θ B (ℓ: arc
// length): with the RMF, ∂d/∂ℓ = −(d·κ) T (κ the curvature vector), so ∂x/∂ℓ = (1 − r d·κ) T +
// r' d, ∂x/∂θ = r (−sin θ N + cos θ B), and
//   n_kj = normalize((1 − r_k d_kj·κ_k) d_kj − r'_k T_k),
// which tilts against a growing radius more on the inside of a bend (1 − r d·κ is clamped at 0.1
// where the radius approaches the radius of curvature and the swept surface would fold).
// End caps close the tube into a closed, consistently oriented 2-manifold:
//   round: hemispheres of radius r at both ends (rings at latitudes φ_c = c π / (2 C), then a
//          pole x ∓ r T), sharing the end rings of the side, with exact sphere normals;
//   flat:  disks; their rim vertices are duplicates of the end rings (normal ∓T, crisp edge),
//          so the mesh is closed once coincident vertices are welded.
// The topology (triangles) is built once; update() rewrites vertices and normals in place in
// O(rings · sides), linear in the number of samples.
#pragma once

#include <vector>

#include "filum/geometry/curve_frame.hpp"
#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

enum class CapStyle { kRound, kFlat };

class GeneralizedCylinder {
 public:
  /// rings >= 2 axis samples, sides >= 3 vertices per ring; cap_rings >= 1 latitude rings per
  /// round cap (0: sides / 4, at least 2). Throws std::invalid_argument.
  GeneralizedCylinder(int rings, int sides, CapStyle caps = CapStyle::kRound, int cap_rings = 0);

  /// Rewrites the vertices and normals around the axis points x (rings × 3) with unit tangents
  /// (rings × 3), curvature vectors κ (rings × 3, 1/m; may be empty: straight), radii r_k > 0 (m)
  /// and slopes dr/dℓ (dimensionless). The first frame's normal is `initial_normal` projected
  /// ⊥ T_0 (pass the previous frame's normal for temporal coherence).
  void update(ConstPointsRef axis, ConstPointsRef unit_tangents, ConstPointsRef curvatures, const VecX& radii,
              const VecX& radius_slopes, const Vec3& initial_normal);

  const TriangleMesh& mesh() const { return mesh_; }
  /// The frames of the last update (one per ring).
  const std::vector<geometry::CurveFrame>& frames() const { return frames_; }
  int rings() const { return rings_; }
  int sides() const { return sides_; }
  CapStyle caps() const { return caps_; }
  int capRings() const { return cap_rings_; }
  /// Index of the side vertex of ring k, angle j.
  int sideVertex(int k, int j) const { return k * sides_ + j; }

 private:
  /// Adds the triangles joining consecutive entries of `sequence` (a ring is its first vertex
  /// index; a single vertex, a pole or a disk centre, is −1 − index), oriented so that the
  /// sequence runs along +T.
  void stitch(const std::vector<int>& sequence, std::vector<Eigen::Vector3i>& out) const;
  void writeCap(int first, int pole, const geometry::CurveFrame& frame, double radius, double direction);

  int rings_, sides_, cap_rings_;
  CapStyle caps_;
  std::vector<double> cos_, sin_;          // cos θ_j, sin θ_j
  std::vector<double> cos_phi_, sin_phi_;  // latitudes of the round caps, c = 1 .. C − 1
  int start_cap_ = 0, end_cap_ = 0;        // first vertex of each cap's rings
  int start_pole_ = 0, end_pole_ = 0;      // pole (round) or disk centre (flat)
  std::vector<geometry::CurveFrame> frames_;
  TriangleMesh mesh_;
};

}  // namespace filum::visual
