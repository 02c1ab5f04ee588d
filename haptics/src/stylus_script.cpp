#include "filum/haptics/stylus_script.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "filum/core/input_file.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::haptics {

namespace {

using Keyframe = geometry::ScriptedPath::Keyframe;

/// A CSV script file: 64 bytes a row at most kMaxWaypoints rows.
constexpr std::uintmax_t kMaxScriptBytes = 64u * kMaxWaypoints;

struct Rows {
  std::vector<Keyframe> keyframes;
  std::vector<unsigned> buttons;
  std::vector<double> rolls;
};

/// The whole of `text` as a number (NaN when it is not one, or has more after it).
double numberOf(const std::string& text) {
  std::size_t used = 0;
  double value = std::nan("");
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    return std::nan("");
  }
  return used == text.size() ? value : std::nan("");
}

/// The whole of `text` as a whole number (NaN when it is not one).
double wholeNumber(const std::string& text) {
  const double value = numberOf(text);
  return value == std::floor(value) && text.find_first_of(".eE") == std::string::npos ? value : std::nan("");
}

/// "time,x,y,z[,buttons[,roll]]" rows; the first line may be a header.
Rows readCsv(const std::string& path) {
  if (const std::string problem = inputFileProblem(path, kMaxScriptBytes); !problem.empty())
    throw SceneError(path, "a CSV file of at most " + byteSize(kMaxScriptBytes) + " (time,x,y,z,buttons rows)", problem);
  std::ifstream in(path);
  Rows rows;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream fields(line);
    double t, x, y, z;
    if (!(fields >> t >> x >> y >> z)) {
      if (number == 1) continue;  // a header
      throw SceneError(path + ":" + std::to_string(number), "a row time,x,y,z[,buttons[,roll]] of numbers",
                       "\"" + line + "\"");
    }
    // An optional fifth column, the buttons: a whole number; an optional sixth, the roll (rad);
    // nothing after them.
    std::string buttons, roll_text, rest;
    double b = 0.0;
    double roll = rows.rolls.empty() ? 0.0 : rows.rolls.back();  // as a waypoint's: the previous row's
    if (fields >> buttons) b = wholeNumber(buttons);
    if (fields >> roll_text) roll = numberOf(roll_text);
    if (fields >> rest || !(b >= 0 && b <= 0xffff) || !std::isfinite(t) || !std::isfinite(x) || !std::isfinite(y) ||
        !std::isfinite(z) || !std::isfinite(roll))
      throw SceneError(path + ":" + std::to_string(number), "finite time,x,y,z, buttons in [0, 65535] and a finite roll",
                       "\"" + line + "\"");
    if (t < 0.0 || (!rows.keyframes.empty() && !(t > rows.keyframes.back().time)))
      throw SceneError(path + ":" + std::to_string(number), "a time >= 0 later than the previous row's", "\"" + line + "\"");
    if (static_cast<int>(rows.keyframes.size()) >= kMaxWaypoints)
      throw SceneError(path + ":" + std::to_string(number), "at most " + std::to_string(kMaxWaypoints) + " rows",
                       "more");
    rows.keyframes.push_back({t, Vec3(x, y, z)});
    rows.buttons.push_back(static_cast<unsigned>(b));
    rows.rolls.push_back(roll);
  }
  if (rows.keyframes.empty()) throw SceneError(path, "at least one row time,x,y,z[,buttons]", "none");
  return rows;
}

Rows readWaypoints(const Params& p) {
  Rows rows;
  const std::vector<Params> items = p.objects("waypoints");
  if (items.empty()) p.fail("waypoints", "at least one waypoint {\"time\": t, \"position\": [x, y, z]}");
  if (static_cast<int>(items.size()) > kMaxWaypoints)
    p.fail("waypoints", "at most " + std::to_string(kMaxWaypoints) + " waypoints");
  for (const Params& item : items) {
    const double t = item.number({"time", "s"});
    if (t < 0.0 || (!rows.keyframes.empty() && !(t > rows.keyframes.back().time)))
      item.fail("time", "a time >= 0 (s) later than the previous waypoint's");
    rows.keyframes.push_back({t, item.vec3({"position", "m"})});
    rows.buttons.push_back(static_cast<unsigned>(item.integer("buttons", 0, 0xffff, 0, "a button mask")));
    rows.rolls.push_back(item.number({"roll", "rad"}, rows.rolls.empty() ? 0.0 : rows.rolls.back()));
    item.finish();
  }
  return rows;
}

}  // namespace

StylusScript::StylusScript(std::vector<Keyframe> keyframes, std::vector<unsigned> buttons,
                           geometry::ScriptedPath::Interpolation interpolation, std::vector<double> rolls)
    : buttons_(std::move(buttons)) {
  times_.reserve(keyframes.size());
  std::vector<Keyframe> roll_keys;
  roll_keys.reserve(keyframes.size());
  for (std::size_t i = 0; i < keyframes.size(); ++i) {
    times_.push_back(keyframes[i].time);
    roll_keys.push_back({keyframes[i].time, Vec3(i < rolls.size() ? rolls[i] : 0.0, 0.0, 0.0)});
  }
  path_ = geometry::ScriptedPath(std::move(keyframes), interpolation);
  roll_path_ = geometry::ScriptedPath(std::move(roll_keys), interpolation);
}

StylusScript StylusScript::fromParams(const Params& p) {
  if (p.has("waypoints") == p.has("csv")) p.fail("waypoints", "either \"waypoints\" or \"csv\" (one of them)");
  Rows rows;
  if (p.has("csv")) {
    std::filesystem::path path = p.string("csv");
    if (path.is_relative() && !p.file().empty()) path = std::filesystem::path(p.file()).parent_path() / path;
    rows = readCsv(path.string());
  } else {
    rows = readWaypoints(p);
  }
  const std::string name = p.string("interpolation", "linear");
  if (name != "linear" && name != "smooth") p.fail("interpolation", "\"linear\" or \"smooth\"");
  return StylusScript(std::move(rows.keyframes), std::move(rows.buttons),
                      name == "smooth" ? geometry::ScriptedPath::Interpolation::kSmooth
                                       : geometry::ScriptedPath::Interpolation::kLinear,
                      std::move(rows.rolls));
}

unsigned StylusScript::buttons(double t) const {
  const auto after = std::upper_bound(times_.begin(), times_.end(), t);
  return after == times_.begin() ? buttons_.front() : buttons_[after - times_.begin() - 1];
}

}  // namespace filum::haptics
