// `filum list TYPE`: a type's parameters read off its own fromParams (ParameterRecorder) — the
// plane's point and normal with their defaults, a required parameter marked so, an optional one
// typed by the check that reads it — for every type this build knows without a crash; a mistyped
// type refused with the closest name.
#include <gtest/gtest.h>

#include <sstream>

#include "filum/all_components.hpp"
#include "filum/list_command.hpp"

namespace filum::app {
namespace {

std::string listing(const std::string& type, int expected_status = 0) {
  std::ostringstream out, err;
  EXPECT_EQ(listParameters(makeFactory(), type, out, err), expected_status) << err.str();
  return out.str() + err.str();
}

TEST(ListCommand, ThePlaneNamesPointAndNormalWithTheirDefaults) {
  const std::string text = listing("PlaneObstacle");
  EXPECT_NE(text.find("point      [0, 0, 0]"), std::string::npos) << text;
  EXPECT_NE(text.find("normal     [0, 0, 1]"), std::string::npos) << text;
  // "friction" is read only when given (readCommon): optional, typed by its check.
  EXPECT_NE(text.find("friction   -         a number >= 0"), std::string::npos) << text;
}

TEST(ListCommand, ARequiredParameterIsMarkedAndTheChecksAreTheComponentsOwn) {
  const std::string text = listing("GreenLagrangeStretching");
  EXPECT_NE(text.find("youngs_modulus"), std::string::npos) << text;
  EXPECT_NE(text.find("required  a number > 0"), std::string::npos) << text;
  const std::string solver = listing("LagrangeMultiplierSolver");
  EXPECT_NE(solver.find("contact_tolerance    1e-06     a number > 0"), std::string::npos) << solver;
}

TEST(ListCommand, EveryKnownTypeIsListedWithoutACrash) {
  const Factory factory = makeFactory();
  for (const std::string& type : factory.typeNames()) {
    std::ostringstream out, err;
    EXPECT_EQ(listParameters(factory, type, out, err), 0) << type << ": " << err.str();
    EXPECT_NE(out.str().find(type + ": "), std::string::npos) << out.str();
    EXPECT_NE(out.str().find("  name "), std::string::npos) << type;
  }
}

TEST(ListCommand, ExclusiveParametersDoNotStopTheList) {
  // "mass" or "density", not both: tried again without the refused one, the list goes on to the
  // parameters read after them.
  const std::string spline = listing("DynamicSpline");
  EXPECT_NE(spline.find("  mass "), std::string::npos) << spline;
  EXPECT_NE(spline.find("  density "), std::string::npos) << spline;
  EXPECT_NE(spline.find("a number > 0"), std::string::npos) << spline;
}

TEST(ListCommand, AMistypedTypeGetsTheClosestName) {
  const std::string text = listing("PlaneObstacel", 2);
  EXPECT_NE(text.find("did you mean \"PlaneObstacle\"?"), std::string::npos) << text;
}

}  // namespace
}  // namespace filum::app
