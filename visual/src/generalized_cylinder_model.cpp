#include "filum/visual/generalized_cylinder_model.hpp"

#include <algorithm>

#include "filum/core/mechanical_state.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::visual {

std::unique_ptr<GeneralizedCylinderModel> GeneralizedCylinderModel::fromParams(const Params& p) {
  Options o;
  // Limits of a skin mesh (rings × sides vertices, rebuilt every frame): as many rings as curve
  // samples in the output (output_settings.hpp), sides far beyond what a picture shows, and at
  // most kMaxSkinVertices in all.
  if (p.has("samples"))
    o.samples = p.integer("samples", 2, 100000, "rings along the axis: the limit of the output's curve samples");
  o.sides = p.integer("sides", 3, 1024, o.sides, "vertices per ring: 1024 are finer than any pixel of a frame");
  if (o.samples && static_cast<long>(*o.samples) * o.sides > kMaxSkinVertices)
    p.fail("samples", "samples × sides <= " + std::to_string(kMaxSkinVertices) +
                          " vertices (a skin mesh is rebuilt every frame; 48 bytes per vertex)",
           std::to_string(*o.samples) + " × " + std::to_string(o.sides));
  if (p.has("radius") || p.has("radius_profile")) o.profile = RadiusProfile::fromParams(p, 1.0);
  const std::string caps = p.string("caps", "round");
  if (caps == "round")
    o.caps = CapStyle::kRound;
  else if (caps == "flat")
    o.caps = CapStyle::kFlat;
  else
    p.fail("caps", "\"round\" or \"flat\"", "\"" + caps + "\"");
  o.cap_rings = p.integer("cap_rings", 1, 1024, 0, "rings of a round cap: at most the sides of the ring");
  auto model = std::make_unique<GeneralizedCylinderModel>(std::move(o));
  model->setMaterial(Material::fromParams(p, Material{Vec3(0.15, 0.3, 0.85), 1.0}));
  return model;
}

void GeneralizedCylinderModel::init(const Scene&) {
  const auto* spline = body().curve();
  if (!spline)
    throw SceneError(origin(), "a GeneralizedCylinder skins a curve body (e.g. a DynamicSpline), but its body " + body().describe() +
                                   " is not one");
  const geometry::SplineBasis& basis = spline->basis();
  const int pieces = static_cast<int>(basis.breakpoints().size()) - 1;
  const int rings = options_.samples.value_or(std::max(16, 6 * pieces));
  // The default rings follow the control points: checked here, before the mesh is allocated.
  if (static_cast<long>(rings) * options_.sides > kMaxSkinVertices)
    throw SceneError(origin(), "a skin of at most " + std::to_string(kMaxSkinVertices) +
                                   " vertices (rings × sides; give fewer \"samples\" or \"sides\")",
                     std::to_string(rings) + " rings × " + std::to_string(options_.sides) + " sides on " +
                         body().describe());
  if (!options_.profile) options_.profile = RadiusProfile(spline->radius());

  // Rings at equal arc length on the rest curve: u_k = k / (m − 1) of the rest length.
  const geometry::ArcLengthParameterization rest(basis, spline->initialPositions());
  mapping_ = std::make_unique<SplineAxisMapping>(basis, rest.equallySpacedAbscissas(rings));
  cylinder_ = std::make_unique<GeneralizedCylinder>(rings, options_.sides, options_.caps, options_.cap_rings);
  axis_.resize(rings, 3);
  tangents_.resize(rings, 3);
  curvatures_.resize(rings, 3);
  radii_.resize(rings);
  slopes_.resize(rings);
  const double length = rest.totalLength();
  for (int k = 0; k < rings; ++k) {
    const double u = static_cast<double>(k) / (rings - 1);
    radii_[k] = options_.profile->radius(u);
    slopes_[k] = length > 0.0 ? options_.profile->slope(u) / length : 0.0;  // dr/dℓ = (dr/du) / L
  }
}

void GeneralizedCylinderModel::update(const SceneState& s) {
  const ConstPointsMap q = body().block(s.q);
  // Positions down: axis points and derivatives (O(rings)).
  mapping_->apply(q, axis_);
  mapping_->applyDerivative(q, tangents_);
  mapping_->applySecondDerivative(q, curvatures_);
  // Unit tangents T = P'/|P'| and curvature vectors κ = (P'' − (P''·T) T) / |P'|²; where P' = 0
  // (a cusp) borrow the neighbour's direction and take κ = 0.
  const int rings = static_cast<int>(axis_.rows());
  int last_good = -1;
  for (int k = 0; k < rings; ++k) {
    const double norm = tangents_.row(k).norm();
    if (norm > 0.0 && std::isfinite(norm)) {
      tangents_.row(k) /= norm;
      const Vec3 t = tangents_.row(k).transpose(), a = curvatures_.row(k).transpose();
      curvatures_.row(k) = ((a - a.dot(t) * t) / (norm * norm)).transpose();
      if (last_good < 0)
        for (int b = 0; b < k; ++b) tangents_.row(b) = tangents_.row(k);
      last_good = k;
    } else {
      curvatures_.row(k).setZero();
      if (last_good >= 0) tangents_.row(k) = tangents_.row(last_good);
    }
  }
  if (last_good < 0) tangents_.rowwise() = Vec3::UnitX().transpose();  // a curve collapsed to a point
  cylinder_->update(axis_, tangents_, curvatures_, radii_, slopes_, normal_);
  normal_ = cylinder_->frames().front().normal;
}

}  // namespace filum::visual
