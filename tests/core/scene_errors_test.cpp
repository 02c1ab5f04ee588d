// Scene-file errors (DESIGN.md "Scene files"): every bad scene in data/bad_scenes/ is refused by
// loadScene before the simulation starts, with a message that names the file, the place of the
// offending value (JSON pointer, or line:column when the text does not parse), what was expected
// and what was found.
#include <gtest/gtest.h>

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

#include "filum/all_components.hpp"
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
    // Not JSON at all: the place is line:column, the parser says what it expected and found.
    {"invalid_json_syntax.json", "7:13", "invalid JSON", "unexpected string literal; expected '}'",
     Target::kUnparsed},
};

// The message of the SceneError that loading `path` throws ("" and a test failure otherwise).
std::string loadError(const std::string& path) {
  try {
    loadScene(path, app::makeFactory());
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
  const auto scene = loadScene(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json", app::makeFactory());
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
      loadScene(bad, "in-memory", app::makeFactory());
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
      loadScene(bad, "in-memory", app::makeFactory());
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
      loadScene(bad, "in-memory", app::makeFactory());
      ADD_FAILURE() << "a gravity of " << c.value << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("in-memory: /gravity/2: expected a finite number (z of a 3-vector [x, y, z]), ") + c.found);
    }
  }
}

// A constraint at the root, which never holds a body, says "the root node" rather than "node ''".
TEST(SceneErrorsData, ConstraintOnTheRootNamesTheRoot) {
  nlohmann::json bad = readJsonFile(std::string(FILUM_TEST_DATA_DIR) + "/minimal_thread.json");
  bad["components"] = nlohmann::json::array({{{"type", "FixedPointConstraint"}, {"abscissa", 0.0}}});
  try {
    loadScene(bad, "in-memory", app::makeFactory());
    ADD_FAILURE() << "a constraint at the root was accepted";
  } catch (const SceneError& e) {
    EXPECT_EQ(std::string(e.what()),
              "in-memory: /components/0: FixedPointConstraint 'FixedPointConstraint' needs a body, but the root node "
              "holds no mechanical state (e.g. a DynamicSpline)");
  }
}

}  // namespace
}  // namespace filum
