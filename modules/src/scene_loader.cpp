#include "filum/core/scene_loader.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

#include "filum/core/body_component.hpp"
#include "filum/core/collision_pipeline.hpp"
#include "filum/core/constraint_solver.hpp"
#include "filum/core/integrator.hpp"
#include "filum/core/input_file.hpp"
#include "filum/core/json_shape.hpp"
#include "filum/core/scene_error.hpp"

namespace filum {

using nlohmann::json;

namespace {

std::unique_ptr<Component> createComponent(const Params& untyped, const Factory& factory) {
  const std::string type = untyped.string("type");
  const std::string name = untyped.string("name", type);
  const std::string object = untyped.string("object", "");
  const Params p = untyped.withOwner(type);
  std::unique_ptr<Component> component;
  try {
    component = factory.create(type, p, p.where("type"));
  } catch (const SceneError&) {
    throw;
  } catch (const std::exception& e) {
    // A check the component's own parameter reading missed (a library refusing a value): the
    // component's place, never an uncaught exception.
    throw SceneError(p.where() + " (" + type + ")", std::string("cannot build the component: ") + e.what());
  }
  component->setName(name);
  component->setOrigin(p.where());
  if (auto* body_component = dynamic_cast<BodyComponent*>(component.get())) {
    body_component->setObjectPath(object);
  } else if (!object.empty()) {
    p.fail("object", "no 'object' (a " + type + " does not act on a body)", "\"" + object + "\"");
  }
  return component;
}

// Nodes and components of a scene, at most: every component is set up, evaluated at every step
// and drawn, and contacts pair collision models two by two; 1,000 nodes and 10,000 components
// are about 100 times the largest reference scenes (11 nodes, 11 components in a node). The
// count is checked as the scene is read, before each node or component is built.
struct SceneBudget {
  static constexpr int kMaxNodes = 1000;
  static constexpr int kMaxComponents = 10000;
  int nodes = 0;
  int components = 0;
};

void spend(const Params& p, const std::string& key, int& used, int maximum, const std::string& what) {
  const nlohmann::json& list = p.raw(key);
  if (!list.is_array()) return;  // objects() says what was expected
  const long long total = static_cast<long long>(used) + static_cast<long long>(list.size());
  if (total > maximum)
    p.fail(key, "at most " + std::to_string(maximum) + " " + what +
                    " in a scene (scene_loader.cpp: each is set up and evaluated at every step; 100 times the largest "
                    "reference scene)",
           "a list of " + std::to_string(list.size()) + ", " + std::to_string(total) + " so far");
  used = static_cast<int>(total);
}

void loadNode(const Params& p, Node& node, const Factory& factory, SceneBudget& budget) {
  if (p.has("components")) {
    spend(p, "components", budget.components, SceneBudget::kMaxComponents, "components");
    for (const Params& c : p.objects("components")) node.addComponent(createComponent(c, factory));
  }
  if (p.has("nodes")) {
    spend(p, "nodes", budget.nodes, SceneBudget::kMaxNodes, "nodes");
    std::set<std::string> names;
    for (const Params& child : p.objects("nodes")) {
      const std::string name = child.string("name");
      if (name.empty() || name.find('/') != std::string::npos)
        child.fail("name", "a non-empty node name without '/'");
      if (!names.insert(name).second) child.fail("name", "a name unique among its sibling nodes");
      loadNode(child, node.addChild(name), factory, budget);
    }
  }
  p.finish();
}

// The component of a role block ("integrator": {...}): it must be of that role, or it would
// count as a second integrator, say, with no place.
template <class Role>
void addRoleComponent(const Params& top, const std::string& key, const std::string& role, Scene& scene,
                      const Factory& factory) {
  if (top.has(key)) {
    const Params block = top.object(key);
    std::unique_ptr<Component> component = createComponent(block, factory);
    if (!dynamic_cast<Role*>(component.get())) {
      const std::string example = factory.defaultFor(role);
      // Built with += (GCC 12's -Wrestrict misfires at LTO on chains of temporaries).
      std::string expected = "a component of role ";
      expected += role;
      if (!example.empty()) expected += " (e.g. \"" + example + "\")";
      std::string found = "\"";
      found += component->typeName();
      found += "\", which is not a ";
      found += role;
      block.fail("type", expected, found);
    }
    scene.root().addComponent(std::move(component));
    return;
  }
  const std::string type = factory.defaultFor(role);
  if (type.empty()) return;
  const json empty = json::object();
  const Params none(empty, top.file(), top.path() + "/" + key, type);
  auto component = factory.create(type, none, top.where(key));
  component->setName(type);
  component->setOrigin(top.where(key) + " (default)");
  scene.root().addComponent(std::move(component));
}

}  // namespace

json readJsonFile(const std::string& path) {
  // A scene is a few kB (the largest reference scene, 12 kB); the document nlohmann builds takes
  // about ten times its text in memory, so 16 MiB of text is far beyond any scene and still
  // far below the machine's memory. A FIFO or a device would block or never end.
  constexpr std::uintmax_t kMaxSceneFileBytes = 16u << 20;
  const std::string problem = inputFileProblem(path, kMaxSceneFileBytes);
  if (problem == "no such file")
    throw SceneError(path, "cannot open the scene file (does it exist and is it readable?)");
  if (!problem.empty())
    throw SceneError(path, "a regular scene file of at most " + byteSize(kMaxSceneFileBytes) +
                               " (the limit keeps the parsed document within memory)", problem);
  std::ifstream in(path);
  if (!in) throw SceneError(path, "cannot open the scene file (does it exist and is it readable?)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  checkJsonShape(text, path);  // depth, duplicate keys and syntax, each with its place
  try {
    return json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::exception& e) {  // the same parser as the shape check's: not expected
    throw SceneError(path, std::string("invalid JSON: ") + e.what());
  }
}

std::unique_ptr<Scene> loadScene(const std::string& path, const Factory& factory) {
  return loadScene(readJsonFile(path), path, factory);
}

std::unique_ptr<Scene> loadScene(const json& document, const std::string& source, const Factory& factory) {
  if (!document.is_object()) throw SceneError(source + ": /", "a JSON object (the scene)", describeJson(document));
  const Params top(document, source, "");
  auto scene = std::make_unique<Scene>();
  SceneSettings& settings = scene->settings();
  settings.source = source;
  settings.name = top.string("name", source);
  settings.dt = top.positive({"dt", "s"}, settings.dt);
  if (settings.dt < kMinTimeStep || settings.dt > kMaxTimeStep)
    top.fail("dt", "a time step in [1e-9, 1] s (scene.hpp: below 1e-9 s no scene gains stability, above 1 s gravity "
                   "alone moves a point 5 m per step)");
  settings.duration = top.positive({"duration", "s"}, settings.duration);
  const std::string steps = stepCountProblem(settings.duration, settings.dt);
  if (!steps.empty())
    top.fail("duration", "a duration of 1 to " + std::to_string(kMaxSteps) +
                             " steps of dt (at least dt / 2; at most 1e8 steps, the step log of `filum run` and "
                             "hours of computing)", steps);
  settings.gravity = top.vec3({"gravity", "m/s²"}, settings.gravity);
  settings.max_speed = top.positive({"max_speed", "m/s"}, settings.max_speed);
  top.has("output");  // read by the applications (filum run), not by the kernel
  top.has("camera");  // read by the visual side
  top.has("haptics");  // read by the applications (haptics/haptic_session.hpp)
  top.has("instruments");  // read by the applications (haptics/instrument_set.hpp)
  top.has("metrics");  // the instruments' trainee metrics (haptics/instrument_set.hpp)
  top.has("needles");  // the needles the instruments hold (haptics/needle.hpp)
  top.has("wound");  // the lips a needle punctures (haptics/wound.hpp)
  top.has("navigation");  // catheter and guidewire metrics (haptics/navigation_metrics.hpp)
  top.has("fluoroscopy");  // the C-arm view and its pedal (visual/fluoroscopy_view.hpp, haptics/fluoroscopy_pedal.hpp)

  addRoleComponent<Integrator>(top, "integrator", "Integrator", *scene, factory);
  addRoleComponent<ConstraintSolver>(top, "constraint_solver", "ConstraintSolver", *scene, factory);
  // The collision pipeline (collision_pipeline.hpp): "collision": {"type": ...}, or the factory's
  // default; it stays idle, never called, unless the scene holds collision models.
  addRoleComponent<CollisionPipeline>(top, "collision", "CollisionPipeline", *scene, factory);
  if (!top.has("nodes")) top.fail("nodes", "a list of nodes (bodies)");
  SceneBudget budget;
  loadNode(top, scene->root(), factory, budget);  // reads "nodes" (and "components" at the root)
  top.finish();
  scene->init();
  return scene;
}

}  // namespace filum
