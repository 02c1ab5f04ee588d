#include "filum/visual/sphere_model.hpp"

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/sphere_mesh.hpp"

namespace filum::visual {

SphereModel::SphereModel(Options options) : options_(std::move(options)), unit_(unitSphere(options_.resolution)) {}

std::unique_ptr<SphereModel> SphereModel::fromParams(const Params& p) {
  Options o;
  int placements = 0;
  if (p.has("center")) {
    o.placement = Placement::kFixed;
    o.center = p.vec3({"center", "m"});
    ++placements;
  }
  if (p.has("abscissa")) {
    o.placement = Placement::kOnCurve;
    o.abscissas = {p.abscissa("abscissa")};
    ++placements;
  }
  if (p.has("abscissas")) {
    o.placement = Placement::kOnCurve;
    const nlohmann::json& list = p.raw({"abscissas", "1"});
    if (!list.is_array() || list.empty()) p.fail("abscissas", "a non-empty list of abscissas in [0, 1]", describeJson(list));
    for (std::size_t i = 0; i < list.size(); ++i) {
      if (!list[i].is_number() || !(list[i].get<double>() >= 0.0 && list[i].get<double>() <= 1.0))
        p.fail("abscissas", "abscissas in [0, 1]", "entry " + std::to_string(i) + " = " + describeJson(list[i]));
      o.abscissas.push_back(list[i].get<double>());
    }
    ++placements;
  }
  if (p.has("count")) {
    o.placement = Placement::kEvenlyOnCurve;
    o.count = p.integer("count", 1, 100000, "one sphere mesh each; the limit of the output's curve samples");
    ++placements;
  }
  if (p.has("constraint")) {
    o.placement = Placement::kConstraintTarget;
    o.constraint = p.string("constraint");
    ++placements;
  }
  if (p.has("path")) {
    o.placement = Placement::kScriptedPath;
    o.path = geometry::ScriptedPath::fromParams(p, "path");
    ++placements;
  }
  if (placements != 1)
    p.fail("", "exactly one of \"center\", \"abscissa\", \"abscissas\", \"count\", \"constraint\" or \"path\"",
           std::to_string(placements) + " of them");
  if (p.has({"radius", "m"})) o.radius = p.positive({"radius", "m"});
  o.resolution = p.integer("resolution", 2, 256, o.resolution, "latitude rings: 256 are finer than any pixel");
  // A sphere mesh has about 2 resolution² vertices, one per sphere: the same budget as a skin.
  const long spheres = o.placement == Placement::kEvenlyOnCurve ? o.count
                      : o.placement == Placement::kOnCurve    ? static_cast<long>(o.abscissas.size())
                                                              : 1;
  const long vertices = 2L * o.resolution * o.resolution * spheres;
  if (vertices > kMaxSkinVertices)
    p.fail(p.has("count") ? "count" : p.has("abscissas") ? "abscissas" : "resolution",
           "spheres × 2 resolution² <= " + std::to_string(kMaxSkinVertices) +
               " vertices (the meshes are rebuilt every frame; generalized_cylinder_model.hpp)",
           std::to_string(vertices) + " vertices");
  auto model = std::make_unique<SphereModel>(std::move(o));
  model->setMaterial(Material::fromParams(p, Material{Vec3(0.85, 0.2, 0.15), 1.0}));
  return model;
}

void SphereModel::init(const Scene& scene) {
  const auto* spline = bound() ? body().curve() : nullptr;
  if (needsBody() && !spline)
    throw SceneError(origin(), "spheres on a curve need a curve body (e.g. a DynamicSpline), but " + body().describe() + " is not one");
  if (options_.radius)
    radius_ = *options_.radius;
  else if (spline)
    radius_ = spline->radius();
  else
    throw SceneError(origin() + "/radius", "a positive radius (m) for a sphere that is not on a spline", "nothing");

  int count = 1;
  radii_.resize(0);
  if (options_.placement == Placement::kOnCurve || options_.placement == Placement::kEvenlyOnCurve) {
    std::vector<double> s = options_.abscissas;
    if (options_.placement == Placement::kEvenlyOnCurve) {
      s = {0.5};
      if (options_.count > 1)
        s = geometry::ArcLengthParameterization(spline->basis(), spline->initialPositions())
                .equallySpacedAbscissas(options_.count);
    }
    mapping_ = std::make_unique<SplineAxisMapping>(spline->basis(), s);
    count = mapping_->outputCount();
    // A radius given here holds for every sphere; else each takes the body's section at its
    // abscissa where that changes along the body (a rod's spans).
    if (!options_.radius && spline->radiusVaries()) {
      radii_.resize(count);
      for (int k = 0; k < count; ++k) radii_[k] = spline->radiusAt(s[k]);
      radius_ = radii_.maxCoeff();
    }
  } else if (options_.placement == Placement::kConstraintTarget && options_.target) {
    constraint_ = options_.target;
  } else if (options_.placement == Placement::kConstraintTarget) {
    for (const Constraint* c : scene.constraints())
      if (c->name() == options_.constraint) constraint_ = c;
    std::string known;
    for (const Constraint* c : scene.constraints()) known += (known.empty() ? "\"" : ", \"") + c->name() + "\"";
    if (!constraint_)
      throw SceneError(origin() + "/constraint", "the name of a constraint of the scene (known: " + known + ")",
                       "\"" + options_.constraint + "\"");
    if (!constraint_->hasTargetPoint())
      throw SceneError(origin() + "/constraint",
                       "a point constraint with a target (e.g. a FixedPointConstraint or a SlidingPointConstraint)",
                       constraint_->describe());
  }
  centers_.setZero(count, 3);
}

void SphereModel::update(const SceneState& s) {
  switch (options_.placement) {
    case Placement::kFixed:
      centers_.row(0) = options_.center.transpose();
      break;
    case Placement::kOnCurve:
    case Placement::kEvenlyOnCurve:
      mapping_->apply(body().block(s.q), centers_);
      break;
    case Placement::kConstraintTarget:
      if (constraint_->releasedAt(s) || !constraint_->active()) {
        centers_.resize(0, 3);  // released: nothing to draw
      } else {
        centers_.resize(1, 3);
        centers_.row(0) = constraint_->targetPoint(s)->transpose();
      }
      break;
    case Placement::kScriptedPath:
      centers_.row(0) = options_.path.position(s.time).transpose();
      break;
  }
  if (radii_.size() > 0)
    sphereSet(unit_, centers_, radii_, mesh_);
  else
    sphereSet(unit_, centers_, radius_, mesh_);
}

}  // namespace filum::visual
