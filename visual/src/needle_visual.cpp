#include "filum/visual/needle_visual.hpp"

#include <cmath>

namespace filum::visual {

NeedleVisual::NeedleVisual(const haptics::Needle& needle)
    : needle_(needle), cylinder_(kRings, 12, CapStyle::kRound) {
  setName(needle.name());
  setMaterial(Material{Vec3(0.72, 0.74, 0.78), 1.0});
}

void NeedleVisual::update(const SceneState&) {
  // The arc P(θ) = c + R (cos θ u + sin θ v): tangent (−sin θ u + cos θ v), curvature −(P − c)/R².
  const haptics::Needle::Settings& s = needle_.settings();
  const haptics::RigidPose& pose = needle_.pose();
  Points axis(kRings, 3), tangents(kRings, 3), curvatures(kRings, 3);
  for (int k = 0; k < kRings; ++k) {
    const double theta = s.arc * k / (kRings - 1);
    const Vec3 radial = pose.rotation * Vec3(std::cos(theta), std::sin(theta), 0.0);
    axis.row(k) = (pose.position + s.radius * radial).transpose();
    tangents.row(k) = (pose.rotation * Vec3(-std::sin(theta), std::cos(theta), 0.0)).transpose();
    curvatures.row(k) = (-radial / s.radius).transpose();
  }
  // The wire tapers to the point over its last tenth.
  VecX radii(kRings), slopes(kRings);
  for (int k = 0; k < kRings; ++k) {
    const double u = static_cast<double>(k) / (kRings - 1);
    radii[k] = s.wire_radius * (u < 0.9 ? 1.0 : std::max(0.15, (1.0 - u) / 0.1));
    slopes[k] = 0.0;
  }
  cylinder_.update(axis, tangents, curvatures, radii, slopes, pose.rotation.col(2));
}

}  // namespace filum::visual
