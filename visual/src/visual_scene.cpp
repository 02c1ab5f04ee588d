#include "filum/visual/visual_scene.hpp"

#include <algorithm>
#include <cctype>
#include <iterator>
#include <set>

#include "filum/core/scene_error.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/visual/generalized_cylinder_model.hpp"
#include "filum/visual/obstacle_model.hpp"
#include "filum/visual/sphere_model.hpp"

namespace filum::visual {

namespace {

std::string safeName(std::string text) {
  for (char& c : text)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.')) c = '_';
  return text;
}

// Default skin colours, one per spline in declaration order.
const Vec3 kPalette[] = {{0.15, 0.3, 0.85}, {0.85, 0.45, 0.1}, {0.2, 0.65, 0.3}, {0.7, 0.2, 0.6}, {0.1, 0.6, 0.7}};

// Runs a model's set-up; a library's own refusal (std::exception) is reported at the model.
template <class SetUp>
void atOrigin(const VisualModel& model, SetUp setUp) {
  try {
    setUp();
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    throw SceneError(model.origin(), model.typeName() + " cannot be set up: " + e.what());
  }
}

}  // namespace

VisualScene::VisualScene(Scene& scene) : scene_(scene), layout_revision_(scene.layoutRevision()) {
  std::vector<VisualModel*> declared;
  scene.root().collect(declared);
  std::set<const MechanicalState*> drawn;
  for (VisualModel* model : declared) {
    Node* node = model->node();
    if (!model->objectPath().empty()) {
      node = scene.root().find(model->objectPath());
      if (!node) {
        std::vector<std::string> paths;
        scene.root().listPaths(paths);
        std::string known;
        for (const auto& p : paths) known += (known.empty() ? "" : ", ") + p;
        throw SceneError(model->origin() + "/object", "the path of an existing node (known nodes: " + known + ")",
                         "\"" + model->objectPath() + "\"");
      }
    }
    MechanicalState* body = node ? node->mechanicalState() : nullptr;
    if (body) {
      atOrigin(*model, [&] { model->bind(*body, scene); });
      if (model->drawsBody()) drawn.insert(body);
    } else if (!model->needsBody()) {
      atOrigin(*model, [&] { model->initWithoutBody(scene); });
    } else {
      const std::string where = model->objectPath().empty() ? model->origin() : model->origin() + "/object";
      const std::string place = !node || node->path().empty() ? "the root node" : "node '" + node->path() + "'";
      throw SceneError(where, model->typeName() + " '" + model->name() + "' follows a body, but " + place +
                                  " holds no mechanical state (put it in the body's node or name one with \"object\")");
    }
    models_.push_back(model);
    names_.push_back(safeName((node && !node->path().empty() ? node->path() + "_" : "") + model->name()));
  }
  // Default skins for the splines nothing draws.
  int colour = 0;
  for (MechanicalState* body : scene.bodies()) {
    const auto* spline = body->curve();
    if (!spline) continue;
    const Vec3 color = kPalette[colour++ % std::size(kPalette)];
    if (drawn.count(body)) continue;
    auto skin = std::make_unique<GeneralizedCylinderModel>(GeneralizedCylinderModel::Options{});
    skin->setName("skin");
    skin->setOrigin(body->origin() + " (default skin)");
    skin->setNode(body->node());
    skin->setMaterial(Material{color, 1.0});
    skin->bind(*body, scene);
    models_.push_back(skin.get());
    names_.push_back(safeName(body->node()->path() + "_skin"));
    defaults_.push_back(std::move(skin));
  }
  addObstacleDefaults(scene);
  addTargetMarkers(scene);
  // Names must be unique (they become file names).
  std::set<std::string> seen;
  for (std::string& name : names_) {
    std::string unique = name;
    for (int k = 2; !seen.insert(unique).second; ++k) unique = name + "_" + std::to_string(k);
    name = unique;
  }
}

void VisualScene::drawBodyWith(const MechanicalState& body, VisualModel& model, const std::string& name) {
  for (std::size_t i = 0; i < models_.size(); ++i) {
    const bool is_default = std::any_of(defaults_.begin(), defaults_.end(),
                                        [&](const std::unique_ptr<VisualModel>& d) { return d.get() == models_[i]; });
    if (!is_default || !models_[i]->bound() || &models_[i]->body() != &body) continue;
    models_.erase(models_.begin() + static_cast<std::ptrdiff_t>(i));
    names_.erase(names_.begin() + static_cast<std::ptrdiff_t>(i));
    break;
  }
  models_.push_back(&model);
  std::string unique = safeName(name);
  for (int k = 2; std::find(names_.begin(), names_.end(), unique) != names_.end(); ++k)
    unique = safeName(name) + "_" + std::to_string(k);
  names_.push_back(unique);
}

void VisualScene::addObstacleDefaults(Scene& scene) {
  std::set<const collision::Obstacle*> drawn;
  for (const VisualModel* model : models_)
    if (const auto* named = dynamic_cast<const ObstacleModel*>(model)) drawn.insert(named->obstacle());
  std::vector<collision::Obstacle*> obstacles;
  scene.root().collect(obstacles);
  for (const collision::Obstacle* obstacle : obstacles) {
    if (drawn.count(obstacle) || obstacle->shape().kind == collision::ObstacleShape::Kind::kNone) continue;
    auto model = std::make_unique<ObstacleModel>(*obstacle);
    const std::string name = obstacle->name().empty() ? obstacle->typeName() : obstacle->name();
    model->setName(name);
    model->setOrigin(obstacle->origin() + " (default drawing)");
    model->setNode(obstacle->node());
    atOrigin(*model, [&] { model->initWithoutBody(scene); });
    models_.push_back(model.get());
    const Node* node = obstacle->node();
    names_.push_back(safeName((node && !node->path().empty() ? node->path() + "_" : "") + name));
    defaults_.push_back(std::move(model));
  }
}

void VisualScene::addTargetMarkers(Scene& scene) {
  std::set<const Constraint*> marked;
  for (const VisualModel* model : models_)
    if (const auto* spheres = dynamic_cast<const SphereModel*>(model))
      if (spheres->markedConstraint()) marked.insert(spheres->markedConstraint());
  for (const Constraint* c : scene.constraints()) {
    if (marked.count(c) || !c->hasTargetPoint()) continue;
    // Size: three radii of the thread it holds, and at least a hundredth of the thread's length
    // (a 3-0 suture's 0.1 mm would be a speck); a hole (a constraint with an abscissa of its own:
    // a sliding point) grey, a grip or a fixed point green.
    double radius = 1e-3;
    if (c->bound() && c->body().curve()) {
      const CurveBody& curve = *c->body().curve();
      const double length = (curve.position(scene.state().q, 1.0) - curve.position(scene.state().q, 0.0)).norm();
      radius = std::max(3.0 * curve.radius(), 0.01 * length);
    }
    SphereModel::Options options;
    options.placement = SphereModel::Placement::kConstraintTarget;
    options.target = c;
    options.radius = radius;
    auto marker = std::make_unique<SphereModel>(options);
    marker->setName(c->name());
    marker->setOrigin(c->origin() + " (default marker)");
    marker->setNode(c->node());
    marker->setMaterial(Material{c->extraDofCount() > 0 ? Vec3(0.5, 0.5, 0.5) : Vec3(0.2, 0.7, 0.3), 1.0});
    atOrigin(*marker, [&] { marker->initWithoutBody(scene); });
    models_.push_back(marker.get());
    const Node* node = c->node();
    names_.push_back(safeName((node && !node->path().empty() ? node->path() + "_" : "") + c->name() + "_marker"));
    defaults_.push_back(std::move(marker));
  }
}

void VisualScene::update(const SceneState& s) {
  // Points were inserted since the last update (Scene::refine): the models that follow a body
  // rebuild their mappings on its new basis.
  if (scene_.layoutRevision() != layout_revision_) {
    for (VisualModel* model : models_)
      if (model->bound()) model->bind(model->body(), scene_);
    layout_revision_ = scene_.layoutRevision();
  }
  for (VisualModel* model : models_) model->update(s);
}

bool VisualScene::bounds(Vec3& lower, Vec3& upper) const {
  bool any = false;
  for (const VisualModel* model : models_) {
    if (!model->framed()) continue;
    for (int i = 0; i < model->meshCount(); ++i) {
      const TriangleMesh& mesh = model->mesh(i);
      if (mesh.vertexCount() == 0) continue;
      Vec3 lo, hi;
      meshBounds(mesh, lo, hi);
      lower = any ? Vec3(lower.cwiseMin(lo)) : lo;
      upper = any ? Vec3(upper.cwiseMax(hi)) : hi;
      any = true;
    }
  }
  return any;
}

}  // namespace filum::visual
