// The scene graph and the component factory: node paths and look-up, the factory's type
// registry (unknown and built-out types), and a reference scene that loads and steps.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/library_components.hpp"
#include "filum/core/factory.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/node.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum {
namespace {

// A component that does nothing: enough to fill nodes and the factory.
class Marker final : public Component {
 public:
  std::string typeName() const override { return "Marker"; }
};

// The message of the SceneError that f() throws, or "" and a test failure.
template <class F>
std::string errorOf(F&& f) {
  try {
    f();
  } catch (const SceneError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no SceneError was thrown";
  return "";
}

// root ─ thread ─ collision
//      └ tool
struct SmallTree {
  Node root{"root"};
  Node& thread = root.addChild("thread");
  Node& collision = thread.addChild("collision");
  Node& tool = root.addChild("tool");
};

// Paths are relative to the root, joined by '/'; the root's own path is empty.
TEST(Node, PathJoinsNamesFromTheRoot) {
  SmallTree tree;
  EXPECT_EQ(tree.root.path(), "");
  EXPECT_EQ(tree.thread.path(), "thread");
  EXPECT_EQ(tree.collision.path(), "thread/collision");
  EXPECT_EQ(tree.tool.path(), "tool");
  EXPECT_EQ(tree.collision.parent(), &tree.thread);
  EXPECT_EQ(tree.root.parent(), nullptr);
}

// find() follows a relative path; an empty path is the node itself; a wrong name gives nullptr.
TEST(Node, FindFollowsRelativePaths) {
  SmallTree tree;
  EXPECT_EQ(tree.root.find(""), &tree.root);
  EXPECT_EQ(tree.root.find("thread"), &tree.thread);
  EXPECT_EQ(tree.root.find("thread/collision"), &tree.collision);
  EXPECT_EQ(tree.thread.find("collision"), &tree.collision);  // relative to the node asked
  EXPECT_EQ(tree.root.find("collision"), nullptr);            // not a child of the root
  EXPECT_EQ(tree.root.find("thread/visual"), nullptr);
  EXPECT_EQ(tree.root.find("threa"), nullptr);  // no prefix matching
}

// listPaths() gives every descendant depth first in declaration order, without the root (the
// list of "known nodes" in error messages).
TEST(Node, ListPathsIsDepthFirstWithoutTheRoot) {
  SmallTree tree;
  std::vector<std::string> paths;
  tree.root.listPaths(paths);
  EXPECT_EQ(paths, (std::vector<std::string>{"thread", "thread/collision", "tool"}));
}

// collect() finds components depth first in declaration order (the determinism contract);
// mechanicalState() is nullptr on a node that holds none.
TEST(Node, CollectIsDepthFirstInDeclarationOrder) {
  SmallTree tree;
  Component& a = tree.root.addComponent(std::make_unique<Marker>());
  Component& c = tree.collision.addComponent(std::make_unique<Marker>());
  Component& b = tree.thread.addComponent(std::make_unique<Marker>());
  Component& d = tree.tool.addComponent(std::make_unique<Marker>());
  std::vector<Marker*> all;
  tree.root.collect(all);
  EXPECT_EQ(all, (std::vector<Marker*>{static_cast<Marker*>(&a), static_cast<Marker*>(&b),
                                       static_cast<Marker*>(&c), static_cast<Marker*>(&d)}));
  std::vector<Marker*> own;
  tree.thread.collect(own, /*recursive=*/false);
  EXPECT_EQ(own, (std::vector<Marker*>{static_cast<Marker*>(&b)}));
  EXPECT_EQ(b.node(), &tree.thread);
  EXPECT_EQ(tree.thread.mechanicalState(), nullptr);
}

// A factory with one type; creating it through Params reads its parameters.
Factory markerFactory() {
  Factory factory;
  factory.add("Marker", "does nothing", [](const Params&) { return std::make_unique<Marker>(); });
  factory.add("Anchor", "does nothing either", [](const Params&) { return std::make_unique<Marker>(); });
  return factory;
}

// Registered types are known, listed in alphabetical order, and created by name.
TEST(Factory, CreatesRegisteredTypes) {
  const Factory factory = markerFactory();
  EXPECT_TRUE(factory.knows("Marker"));
  EXPECT_FALSE(factory.knows("Nope"));
  EXPECT_EQ(factory.typeNames(), (std::vector<std::string>{"Anchor", "Marker"}));
  EXPECT_EQ(factory.summary("Marker"), "does nothing");
  const nlohmann::json empty = nlohmann::json::object();
  const auto component = factory.create("Marker", Params(empty, "f.json", "/c"), "f.json: /c/type");
  EXPECT_EQ(component->typeName(), "Marker");
}

// An unknown type is refused at the place of its "type" key, listing every known type and
// suggesting the nearest (within two edits, or differing in case only).
TEST(Factory, UnknownTypeListsTheKnownOnes) {
  const Factory factory = markerFactory();
  const nlohmann::json empty = nlohmann::json::object();
  EXPECT_EQ(errorOf([&] { factory.create("Makrer", Params(empty, "f.json", "/c"), "f.json: /c/type"); }),
            "f.json: /c/type: expected a known component type (Anchor, Marker), found \"Makrer\" (did you mean "
            "\"Marker\"?)");
  // Nothing close: no suggestion.
  EXPECT_EQ(errorOf([&] { factory.create("Spring", Params(empty, "f.json", "/c"), "f.json: /c/type"); }),
            "f.json: /c/type: expected a known component type (Anchor, Marker), found \"Spring\"");
  // A difference of case alone.
  EXPECT_NE(errorOf([&] { factory.create("marker", Params(empty, "f.json", "/c"), "f.json: /c/type"); })
                .find("(did you mean \"Marker\"?)"),
            std::string::npos);
}

// A type built out of this build names the CMake option that brings it back, instead of
// claiming the type does not exist.
TEST(Factory, BuiltOutTypeNamesItsCMakeOption) {
  Factory factory = markerFactory();
  factory.addUnavailable("VisualModel", "FILUM_WITH_VISUAL");
  EXPECT_FALSE(factory.knows("VisualModel"));
  const nlohmann::json empty = nlohmann::json::object();
  EXPECT_EQ(errorOf([&] { factory.create("VisualModel", Params(empty, "f.json", "/c"), "f.json: /c/type"); }),
            "f.json: /c/type: component type 'VisualModel' was built out; reconfigure with "
            "-DFILUM_WITH_VISUAL=ON to bring it");
  // Registering the type afterwards makes it available; marking an available type unavailable
  // does nothing (a library registered it, so it is built in).
  factory.add("VisualModel", "visual side", [](const Params&) { return std::make_unique<Marker>(); });
  factory.addUnavailable("Marker", "FILUM_WITH_NOTHING");
  EXPECT_TRUE(factory.knows("VisualModel"));
  EXPECT_TRUE(factory.knows("Marker"));
  EXPECT_NO_THROW(factory.create("Marker", Params(empty, "f.json", "/c"), "f.json: /c/type"));
}

// create() refuses parameters the component did not read.
TEST(Factory, CreateRefusesUnreadParameters) {
  const Factory factory = markerFactory();
  const nlohmann::json params = {{"colour", "red"}};
  EXPECT_EQ(errorOf([&] { factory.create("Marker", Params(params, "f.json", "/c", "Marker"), "f.json: /c/type"); }),
            "f.json: /c/colour: unknown parameter 'colour' of Marker (known parameters: none)");
}

// Defaults fill a role a scene leaves out; an unset role has none.
TEST(Factory, DefaultsPerRole) {
  Factory factory = markerFactory();
  EXPECT_EQ(factory.defaultFor("Integrator"), "");
  factory.setDefault("Integrator", "Marker");
  EXPECT_EQ(factory.defaultFor("Integrator"), "Marker");
}

// The application's factory has every library's components and a default for each role.
TEST(Factory, ApplicationFactoryRegistersEveryLibrary) {
  const Factory factory = test::libraryComponents();
  for (const char* type : {"DynamicSpline", "SpringForceField", "ViscousDamping", "SymplecticEuler", "RungeKutta4",
                           "FixedPointConstraint", "LagrangeMultiplierSolver"})
    EXPECT_TRUE(factory.knows(type)) << type;
  EXPECT_EQ(factory.defaultFor("Integrator"), "RungeKutta4");
  EXPECT_EQ(factory.defaultFor("ConstraintSolver"), "LagrangeMultiplierSolver");
}

// The headline scene loads: settings read, components built and bound, and it steps.
TEST(SceneLoader, HangingThreadLoadsAndSteps) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/hanging_thread.json";
  const auto scene = loadScene(path, test::libraryComponents());
  EXPECT_EQ(scene->settings().name, "hanging thread");
  EXPECT_EQ(scene->settings().source, path);
  EXPECT_DOUBLE_EQ(scene->settings().dt, 1e-3);
  EXPECT_DOUBLE_EQ(scene->settings().duration, 2.0);
  EXPECT_EQ(scene->settings().gravity, Vec3(0.0, 0.0, -9.81));
  ASSERT_EQ(scene->bodies().size(), 1u);
  EXPECT_EQ(scene->bodies().front()->pointCount(), 30);
  EXPECT_EQ(scene->bodyAt("thread"), scene->bodies().front());
  EXPECT_EQ(scene->forceFields().size(), 3u);   // stretching, bending, viscous damping
  EXPECT_EQ(scene->constraints().size(), 1u);   // the held end
  EXPECT_EQ(scene->integrator().typeName(), "ImplicitEuler");
  EXPECT_EQ(scene->dofPointCount(), 30);
  // Components remember where they were declared, for later messages.
  EXPECT_EQ(scene->constraints().front()->origin(), path + ": /nodes/0/components/4");
  const StepReport report = scene->step();
  EXPECT_TRUE(report.ok) << report.message;
  EXPECT_EQ(scene->stepCount(), 1);
}

}  // namespace
}  // namespace filum
