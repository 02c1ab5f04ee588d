// Scene-file errors (README, "Scene files"): every bad scene in data/bad_scenes/ is refused by
// loadScene before the simulation starts, with a message that names the file, the place of the
// offending value (JSON pointer, or line:column when the text does not parse), what was expected
// and what was found.
#include <gtest/gtest.h>

#include <sys/stat.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <string>
#include <typeinfo>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/library_components.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"

namespace filum {
namespace {

const std::string kBadScenes = std::string(FILUM_TEST_DATA_DIR) + "/bad_scenes/";

// What the JSON pointer of a message names in the file.
enum class Target {
  kValue,       // the offending value, present in the file
  kMissingKey,  // a required key that is absent: its object is present
  kUnparsed,    // the file does not parse (the pointer, if any, comes from the parser's replay)
};

// One bad scene and the pieces its message must hold.
struct BadScene {
  std::string file;      // in data/bad_scenes/
  std::string place;     // what follows "<path>:" — a JSON pointer, or "L:C" / "L:C: pointer"
  std::string expected;  // what the message says was expected
  std::string found;     // what the message says was found
  Target target = Target::kValue;
};

// For gtest's test names and failure output.
void PrintTo(const BadScene& scene, std::ostream* os) { *os << scene.file; }

const std::vector<BadScene> kCases = {
    // Negative, zero or non-finite physical quantities.
    {"negative_mass.json", " /nodes/0/components/0/mass (DynamicSpline)", "expected a positive number",
     "found -0.001"},
    {"zero_mass.json", " /nodes/0/components/0/mass (DynamicSpline)", "expected a positive number", "found 0"},
    {"zero_density.json", " /nodes/0/components/0/density (DynamicSpline)", "expected a positive number",
     "found 0"},
    {"negative_radius.json", " /nodes/0/components/0/radius (DynamicSpline)", "expected a positive number",
     "found -0.0001"},
    {"zero_length_thread.json", " /nodes/0/components/0/control_points/to (DynamicSpline)",
     "expected a point different from 'from' (a thread of non-zero length)", "found [0.1, 0, 0]"},
    {"zero_time_step.json", " /dt", "expected a positive number", "found 0"},
    // JSON has no NaN or Infinity: 1e999 overflows a double and nlohmann refuses it while parsing,
    // so the place is line:column (of the number's first digit) and the pointer of the value.
    {"infinite_mass.json", "6:16: /nodes/0/components/0/mass", "expected a finite number",
     "found 1e999, which is beyond the range of a double", Target::kUnparsed},
    {"infinite_gravity.json", "3:21: /gravity/2", "expected a finite number",
     "found -1e999, which is beyond the range of a double", Target::kUnparsed},
    {"infinite_control_point.json", "6:53: /nodes/0/components/0/control_points/2/0", "expected a finite number",
     "found 1e999, which is beyond the range of a double", Target::kUnparsed},
    {"string_in_control_point.json", " /nodes/0/components/0/control_points/1/2 (DynamicSpline)",
     "expected a number (z of a point [x, y, z])", "found \"zero\""},
    {"nan_string_abscissa.json", " /nodes/0/components/1/abscissa (FixedPointConstraint)", "expected a number",
     "found \"NaN\""},
    {"string_for_number.json", " /nodes/0/components/0/mass (DynamicSpline)", "expected a number",
     "found \"0.001\""},
    // Curve parameters the basis cannot honour.
    {"too_few_control_points.json", " /nodes/0/components/0/control_points (DynamicSpline)",
     "expected at least 4 control points for a uniform cubic B-spline", "found 3"},
    {"too_few_control_points_count.json", " /nodes/0/components/0/control_points/count (DynamicSpline)",
     "expected an integer >= 4", "found 3"},
    {"abscissa_out_of_range.json", " /nodes/0/components/1/abscissa (FixedPointConstraint)",
     "expected a curve abscissa in [0, 1]", "found 1.5"},
    // References and the node tree.
    {"missing_object_node.json", " /nodes/1/components/0/object",
     "expected the path of an existing node (known nodes: thread, holder)", "found \"threda\""},
    {"constraint_without_body.json", " /nodes/1/components/0",
     "FixedPointConstraint 'FixedPointConstraint' needs a body", "but node 'anchor' holds no mechanical state"},
    {"duplicate_node_names.json", " /nodes/1/name", "expected a name unique among its sibling nodes",
     "found \"thread\""},
    // Parameters: typos, missing, contradictory, out of order.
    {"unknown_parameter.json", " /nodes/0/components/1/bend_stifness",
     "(did you mean 'bend_stiffness'? known parameters: bend_stiffness, damping, name, object, samples, "
     "stretch_stiffness, type)",
     "unknown parameter 'bend_stifness' of SpringForceField"},
    {"misspelled_required_parameter.json", " /nodes/0/components/1/stretch_stiffness (SpringForceField)",
     "expected parameter 'stretch_stiffness'",
     "found nothing (the parameter is missing; is 'stretch_stifness' a misspelling of 'stretch_stiffness'?)",
     Target::kMissingKey},
    {"missing_required_parameter.json", " /nodes/0/components/1/abscissa (FixedPointConstraint)",
     "expected parameter 'abscissa'", "found nothing (the parameter is missing)", Target::kMissingKey},
    {"mass_and_density.json", " /nodes/0/components/0/density (DynamicSpline)",
     "expected either 'mass' or 'density', not both", "found 910"},
    {"scripted_path_decreasing_times.json", " /nodes/0/components/1/path/1/time (FixedPointConstraint)",
     "expected a time later than the previous keyframe's (1.0 s)", "found 0.5"},
    {"unknown_component_type.json", " /nodes/0/components/1/type",
     "expected a known component type (",  // the sorted list grows with every library
     "found \"SpringForceFeild\""},
    // Limits of the machine and of the physics, checked before anything is allocated; each
    // message says where its limit comes from.
    {"huge_control_point_count.json", " /nodes/0/components/0/control_points/count (DynamicSpline)",
     "expected an integer >= 4 and <= 100000 (dynamic_spline.hpp: memory and step time", "found 100000000"},
    {"far_control_point.json", " /nodes/0/components/0/control_points (DynamicSpline)",
     "expected control points within ±1e6 m of the origin", "found point 2 at [1e+308, 0, 0]"},
    {"tiny_density.json", " /nodes/0/components/0/density (DynamicSpline)",
     "expected a density giving a positive, finite mass", "found 5e-324, mass 0.0 kg"},
    {"tiny_mass.json", " /nodes/0/components/0/mass (DynamicSpline)",
     "expected a mass whose matrix M = m ∫ b_i b_j ds is positive definite in double precision",
     "found 5e-324, total mass 5e-324 kg (BandedCholesky: matrix is not positive definite"},
    {"tiny_sphere_spacing.json", " /nodes/0/components/1/spacing",
     "expected at most 1000000 spheres along the thread (sphere_sampling_mapping.hpp",
     "found 100000001.0 spheres of spacing 1e-09 m on 0.1 m"},
    {"huge_mesh_header.json", " /nodes/0/components/1/file (MeshModel)", "expected a readable .obj, .off, .ply, .stl or .vtp mesh",
     "a header announcing 1000000000 vertices and 1 faces in a file of 25 bytes"},
    {"tiny_time_step.json", " /dt", "expected a time step in [1e-9, 1] s (scene.hpp", "found 1e-300"},
    {"short_duration.json", " /duration", "expected a duration of 1 to 100000000 steps of dt",
     "found 0.0001 s, shorter than dt / 2 = 0.0005 s (0 steps)"},
    {"wrong_role_block.json", " /constraint_solver/type", "expected a component of role ConstraintSolver",
     "found \"RungeKutta4\", which is not a ConstraintSolver"},
    // The shape of the text, checked before the document is built: the place is line:column and
    // the pointer of the member that holds the fault.
    {"deeply_nested_array.json", "6:132: /nodes/0/components/0/control_points/count",
     "expected arrays and objects nested at most 64 deep", "found a value nested deeper than that", Target::kUnparsed},
    {"duplicate_key.json", "7:27: /nodes/0/components/0/control_points/count",
     "expected each key once in an object", "found 'count' again; it was first given at line 6, column 65",
     Target::kUnparsed},
    // Not JSON at all: the place is line:column, the parser says what it expected and found.
    {"invalid_json_syntax.json", "7:13", "invalid JSON", "unexpected string literal; expected '}'",
     Target::kUnparsed},
};

// The message of the SceneError that loading `path` throws ("" and a test failure otherwise).
std::string loadError(const std::string& path) {
  try {
    loadScene(path, test::libraryComponents());
  } catch (const SceneError& e) {
    return e.what();
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << " threw a " << typeid(e).name() << " instead of a SceneError: " << e.what();
    return "";
  }
  ADD_FAILURE() << path << " loaded, but should have been refused";
  return "";
}

// The JSON pointer in a place ("6:16: /a/b" or " /a/b (Owner)" -> "/a/b"; "" if none).
std::string pointerOf(const std::string& place) {
  const auto slash = place.find('/');
  if (slash == std::string::npos) return "";
  const auto end = place.find(' ', slash);
  return place.substr(slash, end == std::string::npos ? std::string::npos : end - slash);
}

class SceneErrors : public ::testing::TestWithParam<BadScene> {};

// Each bad scene is refused with a message that starts with the file and the place of the fault
// (so editors and terminals can jump there) and then says what was expected and what was found.
TEST_P(SceneErrors, MessageNamesFilePlaceExpectedAndFound) {
  const BadScene& bad = GetParam();
  const std::string path = kBadScenes + bad.file;
  const std::string message = loadError(path);
  EXPECT_EQ(message.rfind(path + ":" + bad.place + ":", 0), 0u)
      << "should start with '" << path << ":" << bad.place << ":'\n  message: " << message;
  EXPECT_NE(message.find(bad.expected), std::string::npos) << "expected-part missing\n  message: " << message;
  EXPECT_NE(message.find(bad.found), std::string::npos) << "found-part missing\n  message: " << message;
}

// The pointer in the message can be followed in the file: it names the offending value, or for
// a missing key the object that lacks it.
TEST_P(SceneErrors, PointerLeadsToTheFaultInTheFile) {
  const BadScene& bad = GetParam();
  if (bad.target == Target::kUnparsed) return;  // nothing to follow: the place is line:column
  const nlohmann::json document = readJsonFile(kBadScenes + bad.file);
  const nlohmann::json::json_pointer pointer(pointerOf(bad.place));
  ASSERT_FALSE(pointer.empty());
  if (bad.target == Target::kValue) {
    EXPECT_TRUE(document.contains(pointer)) << pointer;
  } else {
    EXPECT_FALSE(document.contains(pointer)) << pointer;
    EXPECT_TRUE(document.at(pointer.parent_pointer()).is_object()) << pointer;
  }
}

INSTANTIATE_TEST_SUITE_P(BadScenes, SceneErrors, ::testing::ValuesIn(kCases),
                         [](const ::testing::TestParamInfo<BadScene>& info) {
                           std::string name = info.param.file.substr(0, info.param.file.find('.'));
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

// Every file in bad_scenes/ has a case above (a new bad scene cannot go untested) and opens with
// a // comment saying what is wrong with it.
TEST(SceneErrorsData, EveryBadSceneIsTestedAndSaysWhatIsWrong) {
  std::set<std::string> tested;
  for (const BadScene& bad : kCases) tested.insert(bad.file);
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(kBadScenes)) {
    if (entry.path().extension() != ".json") continue;
    ++files;
    const std::string name = entry.path().filename().string();
    EXPECT_TRUE(tested.count(name)) << name << " has no case in kCases";
    std::ifstream in(entry.path());
    std::string first_line;
    std::getline(in, first_line);
    EXPECT_EQ(first_line.rfind("// Bad: ", 0), 0u) << name << " should open with '// Bad: <what is wrong>'";
  }
  EXPECT_EQ(files, static_cast<int>(kCases.size()));
}

// The scene the bad scenes vary loads: each bad scene fails because of its one defect.
TEST(SceneErrorsData, TheUnalteredSceneLoads) {
  const auto scene = loadScene(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json", test::libraryComponents());
  EXPECT_EQ(scene->bodies().size(), 1u);
  EXPECT_EQ(scene->constraints().size(), 2u);
}

// A file that does not exist is named in the message.
TEST(SceneErrorsData, MissingFileIsNamed) {
  const std::string path = kBadScenes + "no_such_scene.json";
  const std::string message = loadError(path);
  EXPECT_EQ(message.rfind(path + ": ", 0), 0u) << message;
  EXPECT_NE(message.find("cannot open the scene file"), std::string::npos) << message;
}

// Documents built in memory can hold what a file cannot (NaN, infinity): the parameter checks,
// not the parser, refuse them, and the message says which non-finite value was found.
TEST(SceneErrorsData, NonFiniteNumbersInAParsedDocumentAreRefused) {
  const nlohmann::json good = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  const struct {
    double value;
    const char* found;
  } cases[] = {{std::numeric_limits<double>::infinity(), "found infinity"},
               {-std::numeric_limits<double>::infinity(), "found -infinity"},
               {std::numeric_limits<double>::quiet_NaN(), "found NaN"}};
  for (const auto& c : cases) {
    nlohmann::json bad = good;
    bad["nodes"][0]["components"][0]["mass"] = c.value;
    try {
      loadScene(bad, "in-memory", test::libraryComponents());
      ADD_FAILURE() << "a mass of " << c.value << " was accepted";
    } catch (const SceneError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.rfind("in-memory: /nodes/0/components/0/mass (DynamicSpline): expected a finite number, ", 0),
                0u)
          << message;
      EXPECT_NE(message.find(c.found), std::string::npos) << message;
    }
    // A non-finite control point coordinate is reported at its own pointer (list index, then
    // coordinate index), with its own value.
    bad = good;
    bad["nodes"][0]["components"][0]["control_points"] = {
        {0.0, 0.0, 0.0}, {0.03, 0.0, 0.0}, {c.value, 0.0, 0.0}, {0.09, 0.0, 0.0}, {0.12, 0.0, 0.0}};
    try {
      loadScene(bad, "in-memory", test::libraryComponents());
      ADD_FAILURE() << "a control point at " << c.value << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("in-memory: /nodes/0/components/0/control_points/2/0 (DynamicSpline): "
                            "expected a finite number (x of a point [x, y, z]), ") + c.found);
    }
    // A non-finite coordinate is reported at its own pointer, with its own value.
    bad = good;
    bad["gravity"] = {0.0, 0.0, c.value};
    try {
      loadScene(bad, "in-memory", test::libraryComponents());
      ADD_FAILURE() << "a gravity of " << c.value << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("in-memory: /gravity/2: expected a finite number (z of a 3-vector [x, y, z]), ") + c.found);
    }
  }
}

// Arrays nested 100,000 deep (a stack overflow before): refused by the shape check, which keeps
// its own stack, before nlohmann builds the document.
TEST(SceneErrorsData, NestingFarBeyondTheLimitIsRefusedWithoutRecursion) {
  const std::filesystem::path dir = std::filesystem::path(FILUM_BINARY_DIR) / "test_output" / "deep_nesting";
  std::filesystem::create_directories(dir);
  const std::string path = (dir / "deep.json").string();
  std::ofstream(path) << "{\"nodes\": " << std::string(100000, '[') << std::string(100000, ']') << "}";
  const std::string message = loadError(path);
  EXPECT_EQ(message.rfind(path + ":1:", 0), 0u) << message;
  EXPECT_NE(message.find(": /nodes: expected arrays and objects nested at most 64 deep"), std::string::npos) << message;
}

// A FIFO (or a device) given as the scene or as a mesh file would block forever or never end:
// refused before a byte is read, at the place that names it.
TEST(SceneErrorsData, AFifoIsRefusedAsSceneAndAsMeshFile) {
  const std::filesystem::path dir = std::filesystem::path(FILUM_BINARY_DIR) / "test_output" / "fifo";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  const std::string fifo = (dir / "pipe.off").string();
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  std::string message = loadError(fifo);
  EXPECT_NE(message.find(fifo + ": expected a regular scene file"), std::string::npos) << message;
  EXPECT_NE(message.find("found a FIFO (named pipe)"), std::string::npos) << message;

  nlohmann::json scene = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  for (const char* type : {"MeshModel", "TriangleMeshObstacle"}) {
    if (!test::libraryComponents().knows(type)) continue;  // TriangleMeshObstacle needs FILUM_WITH_CGAL
    nlohmann::json bad = scene;
    bad["nodes"][1]["components"].push_back({{"type", type}, {"file", "pipe.off"}});
    const std::string path = (dir / (std::string(type) + ".json")).string();
    std::ofstream(path) << bad.dump(2);
    message = loadError(path);
    EXPECT_EQ(message.rfind(path + ": /nodes/1/components/1/file (" + std::string(type) + "): expected ", 0), 0u)
        << message;
    EXPECT_NE(message.find("a FIFO (named pipe)"), std::string::npos) << message;
  }
}

// 10,001 components in one node (a mutated copy with 80,000 made a check hang): refused at the
// list, before any of them is built, with the limit and its reason.
TEST(SceneErrorsData, TooManyComponentsAreRefusedBeforeTheyAreBuilt) {
  nlohmann::json bad = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  for (int k = 0; k < 10000; ++k) bad["nodes"][0]["components"].push_back({{"type", "ViscousDamping"}});
  try {
    loadScene(bad, "in-memory", test::libraryComponents());
    ADD_FAILURE() << "10,003 components were accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("in-memory: /nodes/0/components: expected at most 10000 components in a "
                                          "scene (scene_loader.cpp: ",
                                          0),
              0u)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("found a list of 10003, 10003 so far"), std::string::npos) << e.what();
  }
}

// A component of the wrong role placed among a node's components still has a place.
TEST(SceneErrorsData, ASecondIntegratorIsNamedByItsPlace) {
  nlohmann::json bad = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  bad["nodes"][0]["components"].push_back({{"type", "RungeKutta4"}});
  try {
    loadScene(bad, "in-memory", test::libraryComponents());
    ADD_FAILURE() << "a second integrator was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("in-memory: /nodes/0/components/3: expected exactly one integrator", 0), 0u)
        << e.what();
  }
}

// A constraint at the root, which never holds a body, says "the root node" rather than "node ''".
TEST(SceneErrorsData, ConstraintOnTheRootNamesTheRoot) {
  nlohmann::json bad = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  bad["components"] = nlohmann::json::array({{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  try {
    loadScene(bad, "in-memory", test::libraryComponents());
    ADD_FAILURE() << "a constraint at the root was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "in-memory: /components/0: FixedPointConstraint 'FixedPointConstraint' needs a body, but the root node "
              "holds no mechanical state (e.g. a DynamicSpline)");
  }
}

}  // namespace
}  // namespace filum
