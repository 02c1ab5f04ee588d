#include "filum/visual/generalized_cylinder_model.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/mechanical_state.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::visual {

namespace {

/// The body's own section as a profile: its radius, or where the section changes along it (a rod's
/// spans), knots at every breakpoint and every piece's middle with the body's radius there
/// (CurveBody::radiusAt: the larger side's at a breakpoint between two sections), joined by the
/// profile's monotone cubic. A step between two pieces is drawn over the half of the thinner piece
/// next to it, so that the skin covers the thicker section up to the node, as its spheres do.
/// (The profile's u is the fraction of the rest arc length; it is the abscissa of a body whose
/// knots sit at its rest arc lengths, as a FramedChain's — the one body whose section varies.)
RadiusProfile bodyProfile(const CurveBody& body) {
  if (!body.radiusVaries()) return RadiusProfile(body.radius());
  std::vector<double> u = body.sectionAbscissas(), r;
  u.erase(std::unique(u.begin(), u.end()), u.end());  // coincident breakpoints (a knot of multiplicity)
  r.reserve(u.size());
  for (const double at : u) r.push_back(body.radiusAt(at));
  return RadiusProfile(std::move(u), std::move(r));
}

}  // namespace

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
  const CurveBasis& basis = spline->basis();
  const std::vector<Strand> pieces_of_thread = strands(basis);
  const int pieces = static_cast<int>(basis.breakpoints().size()) - 1;
  const int rings = options_.samples.value_or(std::max(16, 6 * pieces));
  // The default rings follow the control points: checked here, before the mesh is allocated
  // (each strand of a cut curve takes at least 2 rings).
  const long all_rings = std::max<long>(rings, 2L * static_cast<long>(pieces_of_thread.size()));
  if (all_rings * options_.sides > kMaxSkinVertices)
    throw SceneError(origin(), "a skin of at most " + std::to_string(kMaxSkinVertices) +
                                   " vertices (rings × sides; give fewer \"samples\" or \"sides\")",
                     std::to_string(all_rings) + " rings × " + std::to_string(options_.sides) + " sides on " +
                         body().describe());
  if (!options_.profile) options_.profile = bodyProfile(*spline);

  // Rings at equal arc length on the rest curve: u_k = ℓ_k / L of the rest length.
  const geometry::ArcLengthParameterization rest(basis, spline->initialPositions());
  const double length = rest.totalLength();
  strands_.clear();
  if (pieces_of_thread.size() == 1) {
    const std::vector<double> s = rest.equallySpacedAbscissas(rings);
    std::vector<double> fractions(rings);
    for (int k = 0; k < rings; ++k) fractions[k] = static_cast<double>(k) / (rings - 1);
    addStrand(basis, pieces_of_thread.front(), s, fractions, length);
    return;
  }
  // A cut curve: the rings shared out by the strands' rest lengths, at least 2 each.
  for (const Strand& strand : pieces_of_thread) {
    const double from = rest.lengthAt(strand.begin), to = rest.lengthAt(strand.end);
    const int count = std::max(2, static_cast<int>(std::lround(rings * (to - from) / length)));
    std::vector<double> fractions(count);
    for (int k = 0; k < count; ++k) fractions[k] = length > 0.0 ? (from + (to - from) * k / (count - 1)) / length : 0.0;
    addStrand(basis, strand, rest.equallySpacedAbscissas(count, strand), fractions, length);
  }
}

void GeneralizedCylinderModel::addStrand(const CurveBasis& basis, const Strand& strand,
                                         const std::vector<double>& s, const std::vector<double>& fractions,
                                         double total_length) {
  const int rings = static_cast<int>(s.size());
  StrandSkin skin;
  skin.mapping = std::make_unique<SplineAxisMapping>(basis, s, strand);
  skin.cylinder = std::make_unique<GeneralizedCylinder>(rings, options_.sides, options_.caps, options_.cap_rings);
  skin.axis.resize(rings, 3);
  skin.tangents.resize(rings, 3);
  skin.curvatures.resize(rings, 3);
  skin.radii.resize(rings);
  skin.slopes.resize(rings);
  for (int k = 0; k < rings; ++k) {
    const double u = fractions[k];
    skin.radii[k] = options_.profile->radius(u);
    skin.slopes[k] = total_length > 0.0 ? options_.profile->slope(u) / total_length : 0.0;  // dr/dℓ = (dr/du) / L
  }
  strands_.push_back(std::move(skin));
}

void GeneralizedCylinderModel::update(const SceneState& s) {
  const ConstPointsMap q = body().block(s.q);
  for (StrandSkin& skin : strands_) updateStrand(skin, q);
}

void GeneralizedCylinderModel::updateStrand(StrandSkin& skin, ConstPointsRef q) {
  // Positions down: axis points and derivatives (O(rings)).
  skin.mapping->apply(q, skin.axis);
  skin.mapping->applyDerivative(q, skin.tangents);
  skin.mapping->applySecondDerivative(q, skin.curvatures);
  // Unit tangents T = P'/|P'| and curvature vectors κ = (P'' − (P''·T) T) / |P'|²; where P' = 0
  // (a cusp) borrow the neighbour's direction and take κ = 0.
  Points& tangents = skin.tangents;
  Points& curvatures = skin.curvatures;
  const int rings = static_cast<int>(skin.axis.rows());
  int last_good = -1;
  for (int k = 0; k < rings; ++k) {
    const double norm = tangents.row(k).norm();
    if (norm > 0.0 && std::isfinite(norm)) {
      tangents.row(k) /= norm;
      const Vec3 t = tangents.row(k).transpose(), a = curvatures.row(k).transpose();
      curvatures.row(k) = ((a - a.dot(t) * t) / (norm * norm)).transpose();
      if (last_good < 0)
        for (int b = 0; b < k; ++b) tangents.row(b) = tangents.row(k);
      last_good = k;
    } else {
      curvatures.row(k).setZero();
      if (last_good >= 0) tangents.row(k) = tangents.row(last_good);
    }
  }
  if (last_good < 0) tangents.rowwise() = Vec3::UnitX().transpose();  // a curve collapsed to a point
  skin.cylinder->update(skin.axis, tangents, curvatures, skin.radii, skin.slopes, skin.normal);
  skin.normal = skin.cylinder->frames().front().normal;
}

}  // namespace filum::visual
