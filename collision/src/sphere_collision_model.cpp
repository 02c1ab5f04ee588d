#include "filum/collision/sphere_collision_model.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "filum/core/node.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/mechanics/dynamic_spline.hpp"  // arcLength

namespace filum::collision {

std::unique_ptr<SphereCollisionModel> SphereCollisionModel::fromParams(const Params& p) {
  Settings s;
  s.radius = p.positive({"radius", "m"}, 0.0);
  s.spacing = p.positive({"spacing", "m"}, 0.0);
  s.self_collision = p.boolean("self_collision", true);
  s.exclusion = p.nonNegative({"exclusion", "m"}, -1.0);
  s.lumen_radius = p.positive({"lumen_radius", "m"}, 0.0);
  if (p.has("lumen_spans")) {
    if (s.lumen_radius == 0.0)
      p.fail("lumen_spans", "a \"lumen_radius\" beside it (the lumen outside the spans; only a tube has a lumen)", "none");
    for (const Params& span : p.objects("lumen_spans")) {
      Settings::LumenSpan l;
      l.from = span.abscissa("from");
      l.to = span.abscissa("to");
      if (!(l.to > l.from)) span.fail("to", "an abscissa above 'from' (" + describeJson(l.from) + ")", describeJson(l.to));
      l.radius = span.positive({"lumen_radius", "m"});
      span.finish();
      for (std::size_t i = 0; i < s.lumen_spans.size(); ++i)
        if (l.from < s.lumen_spans[i].to && s.lumen_spans[i].from < l.to) {
          // (Appended piece by piece: GCC 12's -Wrestrict misfires on "literal" + std::string&&.)
          std::string found = "[";
          found.append(describeJson(l.from)).append(", ").append(describeJson(l.to)).append("] over span ");
          found.append(std::to_string(i)).append(" [").append(describeJson(s.lumen_spans[i].from));
          found.append(", ").append(describeJson(s.lumen_spans[i].to)).append("]");
          span.fail("from", "lumen spans that do not overlap", found);
        }
      s.lumen_spans.push_back(l);
    }
  }
  if (p.has({"lumen_friction", "1"})) s.lumen_friction = p.nonNegative({"lumen_friction", "1"}, 0.0);
  s.inside = p.string("inside", "");
  return std::make_unique<SphereCollisionModel>(s);
}

void SphereCollisionModel::init(const Scene& scene) {
  if (lumen_from_wall_) {  // bound again (a new layout): the wall's lumen is read afresh below
    settings_.lumen_radius = 0.0;
    settings_.lumen_spans.clear();
    lumen_from_wall_ = false;
  }
  MechanicalState* body = node() ? node()->mechanicalState() : nullptr;
  curve_ = body ? body->curve() : nullptr;
  if (!curve_)
    throw SceneError(origin(), "a " + typeName() + " belongs in the node of a curve body such as a DynamicSpline (the thread it samples), "
                                   "but its node holds " + (body ? body->typeName() : std::string("no body")));
  const auto& bodies = scene.bodies();
  body_index_ = static_cast<int>(std::find(bodies.begin(), bodies.end(), body) - bodies.begin());
  point_offset_ = curve_->offset();
  radius_ = settings_.radius > 0.0 ? settings_.radius : curve_->radius();
  smallest_radius_ = radius_;
  // A radius given here holds all along; else the body's section, where it changes along it.
  varies_ = settings_.radius == 0.0 && curve_->radiusVaries();
  if (varies_) {
    const CurveBody::RadiusRange range = curve_->radiusRange();
    radius_ = range.largest;
    smallest_radius_ = range.smallest;
  }
  const double spacing = settings_.spacing > 0.0 ? settings_.spacing : smallest_radius_;
  if (spacing > 2.0 * smallest_radius_)
    throw SceneError(origin() + "/spacing",
                     std::string("a spacing <= 2 radius (") + std::to_string(2.0 * smallest_radius_) + " m" +
                         (varies_ ? ", the body's thinnest section" : "") + ") so that neighbouring spheres touch",
                     std::to_string(spacing) + " m");
  // Checked before the mapping allocates its K ≈ L / h + 1 spheres (a rod's ⌈ℓ_p / h⌉ on each of
  // its pieces: at most one sphere a piece more, within the mapping's own 4× margin).
  const double rest_length = mechanics::arcLength(curve_->basis(), curve_->initialPositions());
  const double spheres = rest_length / spacing + 1.0;
  if (!(spheres <= kMaxSpheresPerThread))
    throw SceneError(origin() + (settings_.spacing > 0.0 ? "/spacing" : "/radius"),
                     "at most " + std::to_string(kMaxSpheresPerThread) +
                         " spheres along the thread (sphere_sampling_mapping.hpp: every step visits each sphere)",
                     describeJson(std::floor(spheres)) + " spheres of spacing " + describeJson(spacing) + " m on " +
                         describeJson(rest_length) + " m");
  if (settings_.lumen_radius == 0.0 && curve_->hollow()) lumenFromWall();
  lumen_varies_ = !settings_.lumen_spans.empty();
  widest_lumen_ = narrowest_lumen_ = settings_.lumen_radius;
  if (lumen_varies_) {  // the lumen's range all along (lumen_radius only where no span covers)
    widest_lumen_ = 0.0;
    narrowest_lumen_ = std::numeric_limits<double>::infinity();
    for (const double s : sectionSamples()) {
      widest_lumen_ = std::max(widest_lumen_, lumenRadiusAt(s));
      narrowest_lumen_ = std::min(narrowest_lumen_, lumenRadiusAt(s));
    }
  }
  checkLumen();
  checkLumenInsideWall();
  if (settings_.lumen_friction && settings_.lumen_radius == 0.0)
    throw SceneError(origin() + "/lumen_friction", "a \"lumen_radius\" beside it (only a tube has a lumen)", "none");
  exclusion_ = settings_.exclusion >= 0.0 ? settings_.exclusion : 4.0 * radius_;
  mapping_ = std::make_unique<SphereSamplingMapping>(curve_->basis(), spacing);
  mapping_->resample(curve_->initialPositions());
  const int capacity = 2 * mapping_->outputCount();  // room for stretching to twice the length
  mapping_->reserve(capacity);
  centers_.resize(capacity, 3);
  velocities_.resize(capacity, 3);
  if (varies_) sphere_radii_.resize(capacity);
  if (lumen_varies_) sphere_lumens_.resize(capacity);
  updateRadii();
}

void SphereCollisionModel::lumenFromWall() {
  // The body's wall is piecewise constant between its breakpoints (sectionAbscissas: breakpoint,
  // middle, breakpoint, ...): lumen_radius is the first piece's lumen, and each run of pieces
  // with another lumen becomes a span. At a span's end lumenRadiusAt takes the narrower side's,
  // as the wall's innerRadiusAt does at a step.
  lumen_from_wall_ = true;
  const std::vector<double> at = curve_->sectionAbscissas();
  settings_.lumen_radius = curve_->innerRadiusAt(at.size() > 1 ? at[1] : 0.0);
  for (std::size_t k = 1; k + 1 < at.size(); k += 2) {
    const double lumen = curve_->innerRadiusAt(at[k]);
    if (lumen == settings_.lumen_radius) continue;
    std::vector<Settings::LumenSpan>& spans = settings_.lumen_spans;
    if (!spans.empty() && spans.back().to == at[k - 1] && spans.back().radius == lumen)
      spans.back().to = at[k + 1];
    else
      spans.push_back({at[k - 1], at[k + 1], lumen});
  }
}

void SphereCollisionModel::checkLumenInsideWall() const {
  // A lumen given here on a body whose section is a tube's wall stays within the wall's own
  // lumen wherever the body has one (an instrument inside meets the wall's inner surface).
  if (settings_.lumen_radius == 0.0) return;
  std::vector<double> at = sectionSamples();
  const std::vector<double> wall = curve_->sectionAbscissas();
  at.insert(at.end(), wall.begin(), wall.end());
  for (const double s : at) {
    const double inner = curve_->innerRadiusAt(s), lumen = lumenRadiusAt(s);
    if (!(inner > 0.0 && lumen > inner)) continue;
    // Named where that lumen is given: the span holding s with that radius, else lumen_radius.
    std::string where = "/lumen_radius";
    for (std::size_t i = 0; i < settings_.lumen_spans.size(); ++i) {
      const Settings::LumenSpan& l = settings_.lumen_spans[i];
      if (l.from <= s && s <= l.to && l.radius == lumen) where = "/lumen_spans/" + std::to_string(i) + "/lumen_radius";
    }
    throw SceneError(origin() + where,
                       "a lumen within the tube's wall: the body's \"inner_radius\" is " + describeJson(inner) +
                           " m at s = " + describeJson(s) + " (or leave \"lumen_radius\" out to take the wall's)",
                       "a lumen of radius " + describeJson(lumen) + " m there");
  }
}

double SphereCollisionModel::lumenRadiusAt(double s) const {
  // The smallest radius of the sections on either side of s within [0, 1]: a span's where it
  // covers that side, else lumen_radius (the spans do not overlap). Span ends are compared exactly:
  // a sphere placed at a span's end by another sum may fall on either side, which moves the
  // lumen's ramp by a chord of the tube's axis (documented as the step's resolution).
  double r = std::numeric_limits<double>::infinity();
  bool left_covered = false, right_covered = false;
  for (const Settings::LumenSpan& l : settings_.lumen_spans) {
    const bool left = l.from < s && s <= l.to, right = l.from <= s && s < l.to;
    if (left || right) r = std::min(r, l.radius);
    left_covered = left_covered || left;
    right_covered = right_covered || right;
  }
  if ((s > 0.0 && !left_covered) || (s < 1.0 && !right_covered)) r = std::min(r, settings_.lumen_radius);
  return r;
}

std::vector<double> SphereCollisionModel::sectionSamples() const {
  // R_in(s) and r(s) are constant between the points where either may step (the body's
  // breakpoints, the spans' ends): those points and the middles between neighbours see every
  // value either takes.
  std::vector<double> at = varies_ ? curve_->sectionAbscissas() : std::vector<double>{0.0, 1.0};
  for (const Settings::LumenSpan& l : settings_.lumen_spans) {
    at.push_back(l.from);
    at.push_back(l.to);
  }
  std::sort(at.begin(), at.end());
  const std::size_t ends = at.size();
  for (std::size_t i = 0; i + 1 < ends; ++i) at.push_back(0.5 * (at[i] + at[i + 1]));
  return at;
}

void SphereCollisionModel::checkLumen() const {
  if (settings_.lumen_radius == 0.0) return;
  for (const double s : sectionSamples()) {  // all along (sectionSamples)
    const double outer = varies_ ? curve_->radiusAt(s) : radius_, lumen = lumenRadiusAt(s);
    if (lumen < outer) continue;
    std::string where = "/lumen_radius";
    for (std::size_t i = 0; i < settings_.lumen_spans.size(); ++i)
      if (settings_.lumen_spans[i].radius == lumen && s >= settings_.lumen_spans[i].from && s <= settings_.lumen_spans[i].to)
        where = std::string("/lumen_spans/").append(std::to_string(i)).append("/lumen_radius");
    throw SceneError(origin() + where,
                     "a lumen radius below the tube's outer radius " + describeJson(outer) + " m" +
                         (varies_ || lumen_varies_ ? " at abscissa " + describeJson(s) : ""),
                     describeJson(lumen) + " m");
  }
}

void SphereCollisionModel::updateRadii() {
  const std::vector<double>& s = mapping_->abscissas();
  if (varies_)
    for (std::size_t k = 0; k < s.size(); ++k) sphere_radii_[k] = curve_->radiusAt(s[k]);
  if (lumen_varies_)
    for (std::size_t k = 0; k < s.size(); ++k) sphere_lumens_[k] = lumenRadiusAt(s[k]);
}

void SphereCollisionModel::update(const SceneState& s) {
  const ConstPointsMap q = curve_->block(s.q);
  const ConstPointsMap v = curve_->block(s.v);
  mapping_->resample(q);
  const int count = mapping_->outputCount();
  if (centers_.rows() < count) {  // grows only when the thread stretched beyond twice its length
    mapping_->reserve(2 * count);
    centers_.resize(2 * count, 3);
    velocities_.resize(2 * count, 3);
    if (varies_) sphere_radii_.resize(2 * count);
    if (lumen_varies_) sphere_lumens_.resize(2 * count);
  }
  updateRadii();
  mapping_->apply(q, centers_.topRows(count));
  mapping_->applyJ(q, v, velocities_.topRows(count));
}

}  // namespace filum::collision
