// GeneralizedCylinderModel (scene type "GeneralizedCylinder"): the skin of a DynamicSpline, a
// generalized cylinder (generalized_cylinder.hpp) around its axis, updated through a
// SplineAxisMapping from the control points:
//   q (mechanical DOFs) → x_k = P(s_k), P'(s_k), P''(s_k) (mapping, O(m)) → RMF frames → rings.
// The m axis samples s_k are placed once, at equal arc length along the rest curve
// (geometry::ArcLengthParameterization), so rings are evenly spaced and each ring stays on the
// same material point of the thread; u_k = k / (m − 1) is then exactly the fraction of the rest
// length that the radius profile is written in.
//
// A cut curve (CurveBody::cut) is skinned strand by strand: one closed tube per strand
// (CurveBasis::strands), its rings shared out by rest length, capped at both ends (the cut ends
// too), so that no triangle spans the gap between the strands. meshCount() is the number of
// strands; u stays the fraction of the whole rest length.
//
// Scene parameters: "samples" (rings, default 6 per polynomial piece, at least 16), "sides"
// (default 16), "radius" (m, default the spline's radius) or "radius_profile" ([[u, r], ...]),
// "caps" ("round" or "flat"), "cap_rings", "color", "opacity".
#pragma once

#include <memory>
#include <optional>

#include "filum/visual/generalized_cylinder.hpp"
#include "filum/visual/radius_profile.hpp"
#include "filum/visual/spline_axis_mapping.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

/// Vertices of one skin mesh, at most (rings × sides): 4e6 vertices take about 200 MB with their
/// normals and triangles, rebuilt every frame.
inline constexpr long kMaxSkinVertices = 4000000;

class GeneralizedCylinderModel final : public VisualModel {
 public:
  struct Options {
    std::optional<int> samples;            // rings along the axis
    int sides = 16;                        // vertices per ring
    std::optional<RadiusProfile> profile;  // default: the spline's radius
    CapStyle caps = CapStyle::kRound;
    int cap_rings = 0;                     // 0: sides / 4
  };
  explicit GeneralizedCylinderModel(Options options) : options_(std::move(options)) {}
  static std::unique_ptr<GeneralizedCylinderModel> fromParams(const Params& p);

  std::string typeName() const override { return "GeneralizedCylinder"; }
  /// X-ray: a body's skin: a wire, a catheter, a coil, a thread (radiopaque jackets and platinum coils: near opaque).
  double defaultXrayOpacity() const override { return 0.85; }
  bool drawsBody() const override { return true; }
  void update(const SceneState& s) override;
  /// One tube per strand of the body (one for an uncut curve).
  int meshCount() const override { return static_cast<int>(strands_.size()); }
  const TriangleMesh& mesh(int strand = 0) const override { return strands_.at(strand).cylinder->mesh(); }

  const GeneralizedCylinder& cylinder(int strand = 0) const { return *strands_.at(strand).cylinder; }
  const SplineAxisMapping& mapping(int strand = 0) const { return *strands_.at(strand).mapping; }
  const RadiusProfile& profile() const { return *options_.profile; }
  /// Axis samples and radii of the strand's tube at the last update (rings × 3, rings).
  const Points& axis(int strand = 0) const { return strands_.at(strand).axis; }
  const VecX& radii(int strand = 0) const { return strands_.at(strand).radii; }

 protected:
  void init(const Scene& scene) override;

 private:
  /// The tube of one strand.
  struct StrandSkin {
    std::unique_ptr<SplineAxisMapping> mapping;
    std::unique_ptr<GeneralizedCylinder> cylinder;
    Points axis, tangents, curvatures;  // rings × 3: x_k, T_k, κ_k (1/m)
    VecX radii, slopes;                 // r_k (m), dr/dℓ_k
    Vec3 normal = Vec3::UnitZ();        // first frame's normal, carried from frame to frame
  };
  /// Builds the tube of `strand` with rings at the abscissas s, at the fractions u_k of the rest
  /// length L (the radius profile's argument).
  void addStrand(const CurveBasis& basis, const Strand& strand, const std::vector<double>& s,
                 const std::vector<double>& fractions, double total_length);
  static void updateStrand(StrandSkin& skin, ConstPointsRef q);

  Options options_;
  std::vector<StrandSkin> strands_;
};

}  // namespace filum::visual
