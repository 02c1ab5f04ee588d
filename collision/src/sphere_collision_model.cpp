#include "filum/collision/sphere_collision_model.hpp"

#include <algorithm>
#include <cmath>

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
  if (p.has({"lumen_friction", "1"})) s.lumen_friction = p.nonNegative({"lumen_friction", "1"}, 0.0);
  s.inside = p.string("inside", "");
  return std::make_unique<SphereCollisionModel>(s);
}

void SphereCollisionModel::init(const Scene& scene) {
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
  if (settings_.lumen_radius > 0.0 && !(settings_.lumen_radius < smallest_radius_))
    throw SceneError(origin() + "/lumen_radius",
                     "a lumen radius below the tube's outer radius " + describeJson(smallest_radius_) + " m" +
                         (varies_ ? " (its thinnest section)" : ""),
                     describeJson(settings_.lumen_radius) + " m");
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
  updateRadii();
}

void SphereCollisionModel::updateRadii() {
  if (!varies_) return;
  const std::vector<double>& s = mapping_->abscissas();
  for (std::size_t k = 0; k < s.size(); ++k) sphere_radii_[k] = curve_->radiusAt(s[k]);
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
  }
  updateRadii();
  mapping_->apply(q, centers_.topRows(count));
  mapping_->applyJ(q, v, velocities_.topRows(count));
}

}  // namespace filum::collision
