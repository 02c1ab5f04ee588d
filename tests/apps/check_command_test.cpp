// `filum check` refuses what `filum run` refuses: besides the scene, it reads the "output" block
// and the "camera", and binds the visual models to the bodies and constraints they follow.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "filum/check_command.hpp"
#include "filum/run_command.hpp"
#include "support/scenes.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;

std::string check(const nlohmann::json& document, const std::string& name, int& status) {
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "check";
  fs::create_directories(dir);
  const fs::path scene = dir / (name + ".json");
  std::ofstream(scene) << document.dump(2);
  std::ostringstream out;
  status = checkScene(scene.string(), out);
  return out.str();
}

TEST(CheckCommand, AGoodSceneIsOk) {
  int status = -1;
  const std::string out = check(test::threadScene({}), "good", status);
  EXPECT_EQ(status, 0) << out;
  EXPECT_NE(out.find(": ok ("), std::string::npos) << out;
  // What shows a unit mistake at a glance: the body's length, radius and mass as the scene gives
  // them (10 cm, 2.86e-6 kg; the polyline through 201 points of a straight curve is its length),
  // and the stiffest mode against dt.
  EXPECT_NE(out.find("length 0.1 m"), std::string::npos) << out;
  EXPECT_NE(out.find("mass 2.86e-06 kg"), std::string::npos) << out;
  EXPECT_NE(out.find("stiffest mode: period"), std::string::npos) << out;
}

TEST(CheckCommand, TheOutputBlockIsChecked) {
  nlohmann::json document = test::threadScene({});
  document["output"] = {{"interval", 0.01}, {"curve_samples", 100000000}};
  int status = -1;
  const std::string out = check(document, "output_samples", status);
  EXPECT_EQ(status, kRunSceneError) << out;
  EXPECT_NE(out.find("output_samples.json: /output/curve_samples: expected an integer >= 2 and <= 100000"),
            std::string::npos)
      << out;
}

TEST(CheckCommand, AnUnknownOutputParameterIsRefused) {
  nlohmann::json document = test::threadScene({});
  document["output"] = {{"intervall", 0.01}};
  int status = -1;
  const std::string out = check(document, "output_typo", status);
  EXPECT_EQ(status, kRunSceneError) << out;
  EXPECT_NE(out.find("output_typo.json: /output/intervall: unknown parameter"), std::string::npos) << out;
}

TEST(CheckCommand, TheConstraintAVisualFollowsMustExist) {
  nlohmann::json document = test::threadScene({});
  document["nodes"][0]["components"].push_back({{"type", "SphereModel"}, {"constraint", "no such hole"}});
  int status = -1;
  const std::string out = check(document, "visual_constraint", status);
  EXPECT_EQ(status, kRunSceneError) << out;
  EXPECT_NE(out.find("visual_constraint.json: /nodes/0/components/"), std::string::npos) << out;
  EXPECT_NE(out.find("no such hole"), std::string::npos) << out;
}

}  // namespace
}  // namespace filum::app
