// `filum list TYPE`: a type's parameters read off its own fromParams (ParameterRecorder) — the
// plane's point and normal with their defaults, a required parameter marked so, an optional one
// typed by the check that reads it — for every type this build knows without a crash; a mistyped
// type refused with the closest name; every quantity with its unit.
#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <vector>

#include "filum/all_components.hpp"
#include "filum/list_command.hpp"

namespace filum::app {
namespace {

std::string listing(const std::string& type, int expected_status = 0) {
  std::ostringstream out, err;
  EXPECT_EQ(listParameters(makeFactory(), type, out, err), expected_status) << err.str();
  return out.str() + err.str();
}

/// The listing's line of one parameter ("" if none), its columns split on runs of spaces.
std::vector<std::string> columns(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("  " + key + " ", 0) != 0) continue;
    std::vector<std::string> out;
    std::size_t at = 2;
    while (at < line.size()) {
      const std::size_t gap = line.find("  ", at);
      out.push_back(line.substr(at, gap == std::string::npos ? std::string::npos : gap - at));
      if (gap == std::string::npos) break;
      at = line.find_first_not_of(' ', gap);
    }
    return out;
  }
  return {};
}

TEST(ListCommand, ThePlaneNamesPointAndNormalWithTheirDefaultsAndUnits) {
  const std::string text = listing("PlaneObstacle");
  EXPECT_EQ(columns(text, "point"), (std::vector<std::string>{"point", "[0, 0, 0]", "m", "[x, y, z]"})) << text;
  EXPECT_EQ(columns(text, "normal"), (std::vector<std::string>{"normal", "[0, 0, 1]", "1", "[x, y, z]"})) << text;
  // "friction" is read only when given (readCommon): optional, typed by its check; Coulomb's μ.
  EXPECT_EQ(columns(text, "friction"), (std::vector<std::string>{"friction", "-", "1", "a number >= 0"})) << text;
}

TEST(ListCommand, AKeyWithAnotherMeaningInOneTypeHasThatTypesUnit) {
  // Coulomb's μ on an obstacle; a sliding point's viscous friction; a tissue's stiffness per metre.
  EXPECT_EQ(columns(listing("SphereObstacle"), "friction").at(2), "1");
  EXPECT_EQ(columns(listing("SlidingPointConstraint"), "friction").at(2), "N·s/m");
  EXPECT_EQ(columns(listing("TissueAttachment"), "stiffness").at(2), "N/m²");
  EXPECT_EQ(columns(listing("ContactPipeline"), "stiffness").at(2), "N/m");
}

TEST(ListCommand, AQuantityReadOnlyWhenGivenSaysItsUnitWhereItsPresenceIsAsked) {
  // Params::has({key, unit}): the listing has the unit though the value is not read without one.
  EXPECT_EQ(columns(listing("DynamicSpline"), "density").at(2), "kg/m³");
  EXPECT_EQ(columns(listing("PointLoad"), "force").at(2), "N");
  EXPECT_EQ(columns(listing("PointLoad"), "torque").at(2), "N·m");
  EXPECT_EQ(columns(listing("GreenLagrangeStretching"), "tensile_strength").at(2), "Pa");
  // A list of keyframes says the units of its entries (time, position).
  EXPECT_EQ(columns(listing("ProbeSphere"), "path").at(2), "s, m");
  EXPECT_EQ(columns(listing("FixedPointConstraint"), "path").at(2), "s, m");
}

TEST(ListCommand, EveryQuantityOfEveryTypeHasAUnitAndNoCountHasOne) {
  // A number, a point or an abscissa is a quantity and must say its unit ("1" for a pure
  // number); an integer is a count, a string or a boolean a choice: no unit. The units are those
  // the components' fromParams state where they read each parameter (Params' Key): a component
  // that reads a quantity without its unit fails here, so the list stays complete.
  const Factory factory = makeFactory();
  for (const std::string& type : factory.typeNames()) {
    std::ostringstream out, err;
    ASSERT_EQ(listParameters(factory, type, out, err), 0) << type;
    std::istringstream lines(out.str());
    std::string line;
    std::getline(lines, line);  // "Type: summary"
    std::getline(lines, line);  // blank
    std::getline(lines, line);  // header: the unit column starts under "unit" (the columns
    ASSERT_NE(line.find("  unit  "), std::string::npos) << type << ": no unit column in " << line;
    const std::size_t unit_at = line.find("  unit  ") + 2;  // before it are ASCII: bytes = columns)
    while (std::getline(lines, line) && line.rfind("  ", 0) == 0) {
      const std::string key = line.substr(2, line.find(' ', 2) - 2);
      if (key == "name" || key == "object" || key == "(no") continue;
      const std::string unit = line[unit_at] == ' ' ? "" : line.substr(unit_at, line.find("  ", unit_at) - unit_at);
      const bool quantity = line.find("a number") != std::string::npos || line.find("[x, y, z]") != std::string::npos ||
                            line.find("a curve abscissa") != std::string::npos;
      const bool count_or_choice = line.find("an integer") != std::string::npos || line.find("  a string") != std::string::npos ||
                                   line.find("true or false") != std::string::npos;
      if (quantity) {
        EXPECT_FALSE(unit.empty()) << type << "." << key << " is a quantity without a unit: " << line;
      }
      if (count_or_choice) {
        EXPECT_TRUE(unit.empty()) << type << "." << key << " is a count or a choice with unit " << unit;
      }
    }
  }
}

TEST(ListCommand, ARequiredParameterIsMarkedAndTheChecksAreTheComponentsOwn) {
  const std::string text = listing("GreenLagrangeStretching");
  EXPECT_EQ(columns(text, "youngs_modulus"), (std::vector<std::string>{"youngs_modulus", "required", "Pa", "a number > 0"}))
      << text;
  const std::string solver = listing("LagrangeMultiplierSolver");
  EXPECT_EQ(columns(solver, "contact_tolerance"),
            (std::vector<std::string>{"contact_tolerance", "1e-06", "1", "a number > 0"}))
      << solver;
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
