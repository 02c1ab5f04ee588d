// The fluoroscopy pedal (haptics/fluoroscopy_pedal.hpp): scripted spans say when the X-ray is on
// and sum to the fluoroscopy time trainers score; a hand takes over from the script keeping the
// time so far; bad spans are refused with the place in the file.
#include <gtest/gtest.h>

#include "filum/core/scene_error.hpp"
#include "filum/haptics/fluoroscopy_pedal.hpp"

namespace filum::haptics {
namespace {

using nlohmann::json;

std::unique_ptr<FluoroscopyPedal> pedal(const json& block) {
  return FluoroscopyPedal::fromScene(json{{"fluoroscopy", block}}, "fluoro.json");
}

// Sums and differences of a few numbers of order 1 s: round-off of a few ulps.
constexpr double kRoundOff = 1e-15;

TEST(FluoroscopyPedal, ScriptedSpansSayWhenTheXRayIsOnAndSumToTheFluoroscopyTime) {
  EXPECT_EQ(FluoroscopyPedal::fromScene(json{{"dt", 1e-3}}, "x.json"), nullptr);  // no block, no pedal
  const auto always = pedal(json::object());
  EXPECT_TRUE(always->on(0.0));
  EXPECT_TRUE(always->on(5.0));
  EXPECT_NEAR(always->time(2.5), 2.5, kRoundOff);
  const auto p = pedal({{"on", {{0.5, 1.5}, {2.0, 2.25}}}});
  EXPECT_FALSE(p->on(0.25));
  EXPECT_TRUE(p->on(0.5));
  EXPECT_FALSE(p->on(1.5));  // [t0, t1)
  EXPECT_TRUE(p->on(2.1));
  EXPECT_NEAR(p->time(0.25), 0.0, kRoundOff);
  EXPECT_NEAR(p->time(1.0), 0.5, kRoundOff);
  EXPECT_NEAR(p->time(1.8), 1.0, kRoundOff);
  EXPECT_NEAR(p->time(10.0), 1.25, kRoundOff);
  const auto never = pedal({{"on", json::array()}});
  EXPECT_FALSE(never->on(1.0));
  EXPECT_EQ(never->time(3.0), 0.0);
}

TEST(FluoroscopyPedal, AHandTakesOverFromTheScriptAndKeepsTheTimeSoFar) {
  const auto p = pedal({{"on", {{0.0, 1.0}}}});
  p->release(0.75);  // the hand lifts the pedal inside the scripted span: 0.75 s so far
  EXPECT_FALSE(p->on(0.8));
  EXPECT_NEAR(p->time(2.0), 0.75, kRoundOff);
  p->press(2.0);
  EXPECT_TRUE(p->on(2.5));
  EXPECT_NEAR(p->time(2.5), 1.25, kRoundOff);
  p->press(2.6);  // pressing a pressed pedal changes nothing
  p->release(3.0);
  EXPECT_NEAR(p->time(4.0), 1.75, kRoundOff);
}

TEST(FluoroscopyPedal, BadSpansAreRefusedWithThePlace) {
  const auto refused = [](const json& on, const std::string& expected) {
    try {
      pedal({{"on", on}});
      ADD_FAILURE() << "accepted " << on.dump();
    } catch (const SceneError& e) {
      EXPECT_NE(std::string(e.what()).find("fluoro.json: /fluoroscopy/on"), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
    }
  };
  refused({{1.0, 0.5}}, "span 0");
  refused({{-1.0, 0.5}}, "span 0");
  refused({{0.0, 1.0}, {0.5, 2.0}}, "disjoint");
  refused({{0.0}}, "span 0");
  refused("always", "spans");
}

}  // namespace
}  // namespace filum::haptics
