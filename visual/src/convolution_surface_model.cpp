#include "filum/visual/convolution_surface_model.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::visual {

std::unique_ptr<ConvolutionSurfaceModel> ConvolutionSurfaceModel::fromParams(const Params& p) {
  Options o;
  if (p.has("radius")) o.radius = p.positive({"radius", "m"});
  o.sharpness = p.nonNegative({"sharpness", "1/m"}, 0.0);
  if (p.has("segments")) o.segments = p.integer("segments", 1);
  if (p.has("facet_size")) o.facet_size = p.positive({"facet_size", "m"});
  if (p.has("approximation")) o.approximation = p.positive({"approximation", "m"});
  o.angle_degrees = p.positive({"angle", "°"}, o.angle_degrees);
  if (o.angle_degrees > 30.0)
    p.fail("angle", "a minimum facet angle in (0, 30] degrees (CGAL's mesher may not terminate above 30)",
           std::to_string(o.angle_degrees));
  o.every = p.integer("every", 1, o.every);
  auto model = std::make_unique<ConvolutionSurfaceModel>(o);
  model->setMaterial(Material::fromParams(p, Material{Vec3(0.9, 0.55, 0.55), 1.0}));
  return model;
}

void ConvolutionSurfaceModel::init(const Scene&) {
  const auto* spline = body().curve();
  if (!spline)
    throw SceneError(origin(), "a ConvolutionSurfaceModel wraps a curve body (e.g. a DynamicSpline), but its body " + body().describe() +
                                   " is not one");
  // A radius given here holds all along; else the body's section, where it changes along it: the
  // kernel is the thickest section's, each chord weighted to its own radius (convolution_surface.hpp),
  // and the mesh's default sizes are the thinnest section's.
  varies_ = !options_.radius && spline->radiusVaries();
  const CurveBody::RadiusRange range = spline->radiusRange();
  radius_ = options_.radius.value_or(range.largest);
  const double finest = varies_ ? range.smallest : radius_;
  segments_ = options_.segments.value_or(4 * (static_cast<int>(spline->basis().breakpoints().size()) - 1));
  criteria_.angle_degrees = options_.angle_degrees;
  criteria_.facet_size = options_.facet_size.value_or(0.5 * finest);
  criteria_.approximation = options_.approximation.value_or(0.05 * finest);
  // One mesh per strand, empty until the first update (which meshes: updates_ starts at 0).
  meshes_.assign(strands(spline->basis()).size(), TriangleMesh{});
  updates_ = 0;
}

void ConvolutionSurfaceModel::update(const SceneState& s) {
  const auto& spline = *body().curve();
  if (updates_++ % options_.every != 0) return;
  const std::vector<Strand> pieces = strands(spline.basis());
  const ConstPointsMap q = body().block(s.q);
  // One surface per strand: a cut tube shows two closed ends, not a blend across the gap (each
  // strand takes the segments in proportion to its share of the parameter range, at least one).
  meshes_.resize(pieces.size());
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    const Strand& strand = pieces[k];
    const int segments = std::max(1, static_cast<int>(std::lround(segments_ * (strand.end - strand.begin))));
    geometry::ConvolutionSurface surface(radius_, options_.sharpness);
    if (varies_)
      surface.addCurve(spline.basis(), q, segments, strand, [&spline](double at) { return spline.radiusAt(at); });
    else
      surface.addCurve(spline.basis(), q, segments, strand);
    // Start inside, at the middle of the strand; the bounding ball holds the whole skeleton plus
    // a margin of four radii (blends reach a little further than one radius).
    const double middle = 0.5 * (strand.begin + strand.end);
    const Vec3 inside = geometry::curvePoint(spline.basis(), q, middle);
    double reach = 0.0;
    for (int j = 0; j <= 64; ++j) {
      BasisRow row;
      evaluateOnStrand(spline.basis(), strand, strand.begin + (strand.end - strand.begin) * j / 64.0, row);
      reach = std::max(reach, (geometry::curvePoint(row, q) - inside).norm());
    }
    meshes_[k] = meshConvolutionSurface(surface, inside, reach + 4.0 * radius_ + criteria_.facet_size, criteria_);
  }
}

}  // namespace filum::visual
