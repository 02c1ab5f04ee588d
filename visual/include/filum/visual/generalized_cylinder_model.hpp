// GeneralizedCylinderModel (scene type "GeneralizedCylinder"): the skin of a DynamicSpline, a
// generalized cylinder (generalized_cylinder.hpp) around its axis, updated through a
// SplineAxisMapping from the control points:
//   q (mechanical DOFs) → x_k = P(s_k), P'(s_k), P''(s_k) (mapping, O(m)) → RMF frames → rings.
// The m axis samples s_k are placed once, at equal arc length along the rest curve
// (geometry::ArcLengthParameterization), so rings are evenly spaced and each ring stays on the
// same material point of the thread; u_k = k / (m − 1) is then exactly the fraction of the rest
// length that the radius profile is written in.
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
  bool drawsBody() const override { return true; }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return cylinder_->mesh(); }

  const GeneralizedCylinder& cylinder() const { return *cylinder_; }
  const SplineAxisMapping& mapping() const { return *mapping_; }
  const RadiusProfile& profile() const { return *options_.profile; }
  /// Axis samples and radii of the last update (rings × 3, rings).
  const Points& axis() const { return axis_; }
  const VecX& radii() const { return radii_; }

 protected:
  void init(const Scene& scene) override;

 private:
  Options options_;
  std::unique_ptr<SplineAxisMapping> mapping_;
  std::unique_ptr<GeneralizedCylinder> cylinder_;
  Points axis_, tangents_, curvatures_;  // rings × 3: x_k, T_k, κ_k (1/m)
  VecX radii_, slopes_;     // r_k (m), dr/dℓ_k
  Vec3 normal_ = Vec3::UnitZ();  // first frame's normal, carried from frame to frame
};

}  // namespace filum::visual
