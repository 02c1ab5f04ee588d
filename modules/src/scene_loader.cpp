#include "filum/core/scene_loader.hpp"

#include <fstream>
#include <set>
#include <sstream>
#include <vector>

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

// Replays a text that failed to parse through nlohmann's SAX interface, following the JSON
// pointer of the value being read, to say where the error is and which value it concerns.
class ErrorLocator final : public json::json_sax_t {
 public:
  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(json::number_integer_t) override { return value(); }
  bool number_unsigned(json::number_unsigned_t) override { return value(); }
  bool number_float(json::number_float_t, const json::string_t&) override { return value(); }
  bool string(json::string_t&) override { return value(); }
  bool binary(json::binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool key(json::string_t& key) override {
    frames_.back().key = key;
    return true;
  }
  bool end_object() override { return close(); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_array() override { return close(); }
  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception&) override {
    position_ = position;
    token_ = token;
    for (const Frame& f : frames_) {
      pointer_ += '/';
      pointer_ += f.array ? std::to_string(f.index) : escapePointer(f.key);
    }
    return false;
  }

  std::size_t position() const { return position_; }  // characters read when the error came
  const std::string& token() const { return token_; }  // the offending token
  const std::string& pointer() const { return pointer_; }  // JSON pointer of the value being read

 private:
  struct Frame {
    bool array;
    std::size_t index;  // of the next element, in an array
    std::string key;    // of the current member, in an object
  };
  bool open(bool array) {
    frames_.push_back({array, 0, ""});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  // A value is complete: in an array, the next one gets the next index.
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }

  std::vector<Frame> frames_;
  std::size_t position_ = 0;
  std::string token_;
  std::string pointer_;
};

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
  } catch (const json::exception& e) {
    // Syntax errors (json::parse_error) and numbers beyond the range of a double, such as 1e999
    // (json::out_of_range 406), which nlohmann refuses while parsing: locate both by a replay.
    ErrorLocator locator;
    json::sax_parse(text, &locator, json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/true);
    int line = 0, column = 0;
    lineAndColumn(text, locator.position() > 0 ? locator.position() - 1 : 0, line, column);
    if (e.id == 406) {
      // The lexer stops at the number's last character; point at its first.
      column -= static_cast<int>(locator.token().size()) - 1;
      throw SceneError(path + ":" + std::to_string(line) + ":" + std::to_string(column) + ": " + locator.pointer(),
                       "a finite number", locator.token() + ", which is beyond the range of a double (about 1.8e308)");
    }
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
  // The collision pipeline (collision_pipeline.hpp): "collision": {"type": ...}, or the factory's
  // default; it stays idle, never called, unless the scene holds collision models.
  addRoleComponent(top, "collision", "CollisionPipeline", *scene, factory);
  if (!top.has("nodes")) top.fail("nodes", "a list of nodes (bodies)");
  loadNode(top, scene->root(), factory);  // reads "nodes" (and "components" at the root)
  top.finish();
  scene->init();
  return scene;
}

}  // namespace filum
