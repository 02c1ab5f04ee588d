// VesselTree: a lumen — the inside of an artery and its branches — given by centrelines with
// radii, queried as a signed distance field (positive inside the lumen, in metres) with its
// gradient. What catheters, guidewires and coils touch from inside (collision/vessel_lumen_
// obstacle.hpp), and what the pictures draw (visual/vessel_lumen_model.hpp meshes its surface).
//
// Field. A branch is a polyline of centre points p_0 … p_m with radii r_0 … r_m. A segment k is a
// tapered tube (a cone with spherical ends): at the point of the axis nearest x,
//   t = clamp((x − p_k)·d_k / |d_k|², 0, 1),  d_k = p_{k+1} − p_k,
//   φ_k(x) = r_k + t (r_{k+1} − r_k) − |x − p_k − t d_k|,
// positive inside. A branch is the union of its segments, φ_b = max_k φ_k: consecutive segments
// share their end spheres, so the wall is continuous, and smooth on the outer side of a bend; on
// its inner side two cones meet in a crease (C⁰) whose normals differ by the centreline's turn
// there (5° along the shipped arch, up to 28° at the left subclavian's waypoint). An end marked open (an inlet, an outlet) is not
// closed by its sphere: t is not clamped there, the tube goes on straight with the end radius, so
// that an instrument leaving the model through an outlet, or entering it through the inlet,
// meets no wall across the opening.
// The tree is the union of its branches joined smoothly: the largest two branch fields at x
// combined by the polynomial smooth maximum of blend width k (a fillet at every ostium instead of
// a crease; taking the two largest keeps it symmetric in the branches and within k/4 of the max),
//   smax(a, b) = max(a, b) + h² k / 4,  h = max(k − |a − b|, 0) / k,
// ∇smax = w ∇a + (1 − w) ∇b, w = ½ + (a − b) / (2k) clamped to [0, 1]. It equals the plain
// maximum wherever the two fields differ by more than k, so away from junctions each branch's
// radius is exact. φ is a distance to first order near the wall (|∇φ| = 1 exactly on a cylinder,
// √(1 + r'²) on a taper of slope r'; inside a fillet |∇φ| falls to about 0.7 at a right-angled
// ostium, where φ / |∇φ| overestimates the distance by up to the fillet's k/4); contact takes
// n = ∇φ / |∇φ| and the distance φ / |∇φ|. The capped ends of pictures cut the end segment only:
// the sphere ending the segment before it may show beyond the cut on a short last segment.
//
// File (JSON, documented in docs/vessels.md):
//   {"units": "mm", "blend": 3,
//    "branches": [{"name": "aorta", "open": ["start"], "points": [[x, y, z, r], ...]}, ...]}
// "units" ("m", "cm" or "mm") apply to points, radii and blend; "open" lists "start" and/or "end".
#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::geometry {

class VesselTree {
 public:
  /// Limits checked before anything is allocated (a file is untrusted input).
  static constexpr int kMaxBranches = 256;
  static constexpr int kMaxPoints = 100000;

  struct Branch {
    std::string name;
    Points points;         // m × 3 centre points (m)
    VecX radii;            // m radii (m)
    bool open_start = false, open_end = false;
  };
  /// The field at a point: φ (m, positive inside), ∇φ, and the branch whose field is largest there.
  struct Sample {
    double value = 0.0;
    Vec3 gradient = Vec3::Zero();
    int branch = -1;  // -1: no branch near (φ below −(blend + margin) everywhere: far outside)
  };

  VesselTree() = default;
  /// Branches (each >= 2 points, radii > 0, consecutive points distinct), blend width k >= 0 (m).
  /// Throws std::invalid_argument naming the branch and point.
  VesselTree(std::vector<Branch> branches, double blend);

  /// The tree described by a JSON object as in the header ("units", "blend", "branches"); errors
  /// are SceneErrors naming p's file and JSON path.
  static VesselTree fromParams(const Params& p);
  /// The tree in a JSON file (errors name the file and the JSON path in it).
  static VesselTree read(const std::string& path);

  /// φ and ∇φ at x, computed exactly where φ > −reach (m) — the wall and a band `reach` outside
  /// it; farther outside the lumen Sample::branch is −1 and the value only a bound (φ <= −reach).
  /// With `capped`, open ends are closed by their end planes instead (a flat cut across the tube,
  /// as a segmented vessel ends): what a picture of the model draws.
  Sample sample(const Vec3& x, double reach, bool capped = false) const;
  /// φ of branch b alone (its tube, no blending), m.
  double branchValue(int b, const Vec3& x) const;
  /// The branch x lies in: the one of largest φ_b (−1 if none is within `reach` of x).
  int branchAt(const Vec3& x, double reach) const;

  int branchCount() const { return static_cast<int>(branches_.size()); }
  const Branch& branch(int b) const { return branches_[b]; }
  /// Index of the branch named `name`, −1 if none.
  int branchIndex(const std::string& name) const;
  double blend() const { return blend_; }
  double maxRadius() const { return max_radius_; }
  /// Box around every centre point, grown by the largest radius (open ends go on beyond it).
  const Eigen::AlignedBox3d& bounds() const { return bounds_; }

 private:
  struct Segment {
    Vec3 a, d;            // start and direction p_{k+1} − p_k
    double inv_length2;   // 1 / |d|²
    double ra, dr;        // radius at the start, change along the segment
    bool open_before, open_after;  // t not clamped below 0 / above 1
    Vec3 centre;          // midpoint (culling)
    double cull_radius;   // half length + largest radius: φ_k < −c when |x − centre| > cull_radius + c
  };
  /// φ_k and ∇φ_k of one segment.
  static double segmentValue(const Segment& s, const Vec3& x, bool capped, Vec3& gradient);
  /// φ_b and ∇φ_b of branch b, from its segments within `cull` of x; false when none is (φ_b < −cull).
  bool branchField(int b, const Vec3& x, double cull, bool capped, double& value, Vec3& gradient) const;

  std::vector<Branch> branches_;
  std::vector<Segment> segments_;
  std::vector<int> branch_first_;  // first segment of each branch (+ one past the last)
  double blend_ = 0.0;
  double max_radius_ = 0.0;
  Eigen::AlignedBox3d bounds_;
};

}  // namespace filum::geometry
