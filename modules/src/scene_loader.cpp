#include "filum/core/scene_loader.hpp"

#include <fstream>
#include <set>
#include <sstream>

#include "filum/core/body_component.hpp"
#include "filum/core/scene_error.hpp"

namespace filum {

using nlohmann::json;

namespace {

void lineAndColumn(const std::string& text, std::size_t byte, int& line, int& column) {
  line = 1;
  column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

std::unique_ptr<Component> createComponent(const Params& untyped, const Factory& factory) {
  const std::string type = untyped.string("type");
  const std::string name = untyped.string("name", type);
  const std::string object = untyped.string("object", "");
  const Params p = untyped.withOwner(type);
  std::unique_ptr<Component> component = factory.create(type, p, p.where("type"));
  component->setName(name);
  component->setOrigin(p.where());
  if (auto* body_component = dynamic_cast<BodyComponent*>(component.get())) {
    body_component->setObjectPath(object);
  } else if (!object.empty()) {
    p.fail("object", "no 'object' (a " + type + " does not act on a body)", "\"" + object + "\"");
  }
  return component;
}

void loadNode(const Params& p, Node& node, const Factory& factory) {
  if (p.has("components"))
    for (const Params& c : p.objects("components")) node.addComponent(createComponent(c, factory));
  if (p.has("nodes")) {
    std::set<std::string> names;
    for (const Params& child : p.objects("nodes")) {
      const std::string name = child.string("name");
      if (name.empty() || name.find('/') != std::string::npos)
        child.fail("name", "a non-empty node name without '/'");
      if (!names.insert(name).second) child.fail("name", "a name unique among its sibling nodes");
      loadNode(child, node.addChild(name), factory);
    }
  }
  p.finish();
}

void addRoleComponent(const Params& top, const std::string& key, const std::string& role, Scene& scene,
                      const Factory& factory) {
  if (top.has(key)) {
    scene.root().addComponent(createComponent(top.object(key), factory));
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
  std::ifstream in(path);
  if (!in) throw SceneError(path, "cannot open the scene file (does it exist and is it readable?)");
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  try {
    return json::parse(text, nullptr, /*allow_exceptions=*/true, /*ignore_comments=*/true);
  } catch (const json::parse_error& e) {
    int line = 0, column = 0;
    lineAndColumn(text, e.byte > 0 ? e.byte - 1 : 0, line, column);
    throw SceneError(path + ":" + std::to_string(line) + ":" + std::to_string(column),
                     std::string("invalid JSON: ") + e.what());
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
  settings.dt = top.positive("dt", settings.dt);
  settings.duration = top.positive("duration", settings.duration);
  settings.gravity = top.vec3("gravity", settings.gravity);
  settings.max_speed = top.positive("max_speed", settings.max_speed);
  top.has("output");  // read by the applications (filum run), not by the kernel
  top.has("camera");  // read by the visual side

  addRoleComponent(top, "integrator", "Integrator", *scene, factory);
  addRoleComponent(top, "constraint_solver", "ConstraintSolver", *scene, factory);
  if (!top.has("nodes")) top.fail("nodes", "a list of nodes (bodies)");
  loadNode(top, scene->root(), factory);  // reads "nodes" (and "components" at the root)
  top.finish();
  scene->init();
  return scene;
}

}  // namespace filum
