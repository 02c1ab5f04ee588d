#include "filum/core/params.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <vector>

#include "filum/core/scene_error.hpp"

namespace filum {

using nlohmann::json;

// Levenshtein distance between two keys (insertions, deletions, substitutions).
std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

namespace {

// A typo of `key`: at most two edits away, and the key is long enough for that to mean something.
bool looksLikeMisspelling(const std::string& candidate, const std::string& key) {
  return key.size() > 3 && candidate != key && editDistance(candidate, key) <= 2;
}

}  // namespace

std::string escapePointer(const std::string& key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

std::string describeJson(const json& value) {
  switch (value.type()) {
    case json::value_t::object: return "an object";
    case json::value_t::array: {
      // Short arrays in full, so that a wrong point shows its coordinates: "[0.1, 0, 0]".
      if (value.size() <= 4) {
        std::string text = "[";
        for (std::size_t i = 0; i < value.size(); ++i) text += (i > 0 ? ", " : "") + describeJson(value[i]);
        text += "]";
        if (text.size() <= 60) return text;
      }
      return "an array of " + std::to_string(value.size());
    }
    case json::value_t::null: return "null";
    case json::value_t::number_float: {
      const double d = value.get<double>();
      if (std::isnan(d)) return "NaN";
      if (std::isinf(d)) return d > 0.0 ? "infinity" : "-infinity";
      return value.dump();
    }
    default: {
      std::string text = value.dump();
      if (text.size() > 60) text = text.substr(0, 57) + "...";
      return text;
    }
  }
}

namespace {
thread_local ParameterRecorder* active_recorder = nullptr;

std::string numberText(double d) {
  std::ostringstream text;
  text << d;
  return text.str();
}
std::string vec3Text(const Vec3& v) {
  // One stream, not "[" + std::string: GCC 12 warns falsely (-Wrestrict) on a literal + temporary.
  std::ostringstream text;
  text << '[' << v.x() << ", " << v.y() << ", " << v.z() << ']';
  return text.str();
}
}  // namespace

// `count` distinct points along x, 1 cm apart (a placeholder polyline).
static json placeholderPoints(int count) {
  json points = json::array();
  for (int i = 0; i < std::max(count, 8); ++i) points.push_back({0.01 * i, 0.0, 0.0});
  return points;
}

// Recording, and the key is not in the object: an accessor with a default returns the default
// (valid by construction), one without returns a placeholder.
static bool absentWhileRecording(const json& obj, const std::string& key) {
  return active_recorder && !(obj.is_object() && obj.contains(key));
}

ParameterRecorder::ParameterRecorder() : outer_(active_recorder) { active_recorder = this; }
ParameterRecorder::~ParameterRecorder() { active_recorder = outer_; }

std::string Params::recordedKey(const std::string& key) const {
  return path_.empty() ? key : path_.substr(1) + "/" + key;
}

void Params::record(const Key& key, const std::string& expected, const std::string& fallback) const {
  if (!active_recorder) return;
  // The key as a path below the component's object ("outer/key" for a nested one): the recorded
  // component's own Params has the empty path (ParameterRecorder's use).
  const std::string full = recordedKey(key);
  active_recorder->last_key_ = full;
  auto& reads = active_recorder->reads_;
  for (ParameterRead& r : reads)
    if (r.key == full) {
      if (r.expected.empty()) r.expected = expected;  // first asked by has(): optional, now typed
      if (r.unit.empty()) r.unit = key.unit;
      return;
    }
  // expected "" : has() asked first (a parameter read when given, with no default: optional, or
  // required by a check of the component's own).
  reads.push_back({full, expected, expected.empty() ? "-" : fallback, !expected.empty() && fallback.empty(), key.unit});
}

const json& Params::require(const std::string& key, const json& placeholder) const {
  if (active_recorder && !(obj_.is_object() && obj_.contains(key))) {
    known_.insert(key);
    return active_recorder->placeholders_.emplace_back(placeholder);
  }
  return require(key);
}

Params::Params(const json& obj, std::string file, std::string path, std::string owner)
    : obj_(obj), file_(std::move(file)), path_(std::move(path)), owner_(std::move(owner)) {}

bool Params::has(const Key& key) const {
  known_.insert(key.name);
  record(key, "", "");
  // Recording, every parameter is "given" (as a placeholder), unless the recorder was told
  // otherwise: the reads it guards run and say what the parameter must be.
  if (obj_.is_object() && obj_.contains(key.name)) return true;
  return active_recorder && !active_recorder->treatedAsAbsent(recordedKey(key.name));
}

std::string Params::pointer(const std::string& key) const {
  return key.empty() ? path_ : path_ + "/" + escapePointer(key);
}

std::string Params::where(const std::string& key) const {
  const std::string at = pointer(key);
  return file_ + ": " + (at.empty() ? "/" : at);
}

void Params::fail(const std::string& key, const std::string& expected) const {
  if (obj_.is_object() && obj_.contains(key)) fail(key, expected, describeJson(obj_.at(key)));
  if (active_recorder) fail(key, expected, "the placeholder of `filum list`");
  fail(key, expected, missing(key));
}

void Params::fail(const std::string& key, const std::string& expected, const std::string& found) const {
  failAt(pointer(key), expected, found);
}

void Params::failAt(const std::string& at, const std::string& expected, const std::string& found) const {
  // The owner goes with the place, so that `expected` reads on its own:
  // "f.json: /nodes/0/components/0/mass (DynamicSpline): expected a positive number, found -1".
  const std::string owner = owner_.empty() ? "" : " (" + owner_ + ")";
  throw SceneError(file_ + ": " + (at.empty() ? "/" : at) + owner, expected, found);
}

std::string Params::missing(const std::string& key) const {
  if (obj_.is_object())
    for (const auto& item : obj_.items())
      if (!known_.count(item.key()) && looksLikeMisspelling(item.key(), key))
        return "nothing (the parameter is missing; is '" + item.key() + "' a misspelling of '" + key + "'?)";
  return "nothing (the parameter is missing)";
}

const json& Params::require(const std::string& key) const {
  if (active_recorder && !(obj_.is_object() && obj_.contains(key))) return require(key, json());
  if (!has(key)) fail(key, "parameter '" + key + "'", missing(key));
  return obj_.at(key);
}

double Params::number(const Key& key) const {
  record(key, "a number", "");
  const json& value = require(key, 1.0);
  if (!value.is_number()) fail(key, "a number");
  const double d = value.get<double>();
  if (!std::isfinite(d)) fail(key, "a finite number");
  return d;
}

double Params::number(const Key& key, double fallback) const {
  record(key, "a number", numberText(fallback));
  return has(key) && !absentWhileRecording(obj_, key) ? number(key) : fallback;
}

double Params::positive(const Key& key) const {
  record(key, "a number > 0", "");
  const double d = number(key);
  if (!(d > 0.0)) fail(key, "a positive number");
  return d;
}

double Params::positive(const Key& key, double fallback) const {
  record(key, "a number > 0", numberText(fallback));
  return has(key) && !absentWhileRecording(obj_, key) ? positive(key) : fallback;
}

double Params::nonNegative(const Key& key, double fallback) const {
  record(key, "a number >= 0", numberText(fallback));
  if (!has(key) || absentWhileRecording(obj_, key)) return fallback;
  const double d = number(key);
  if (d < 0.0) fail(key, "a number >= 0");
  return d;
}

double Params::abscissa(const Key& key) const {
  record({key.name, "1"}, "a curve abscissa in [0, 1]", "");
  if (active_recorder && !(obj_.is_object() && obj_.contains(key.name))) return 0.5;
  const double d = number(key);
  if (d < 0.0 || d > 1.0) fail(key, "a curve abscissa in [0, 1]");
  return d;
}

int Params::integer(const Key& key, int minimum) const {
  // 1e8: no count of a scene comes near it, and it fits an int with room for the sums of counts.
  return integer(key, minimum, 100000000, "the largest count any scene parameter takes");
}

int Params::integer(const Key& key, int minimum, int maximum, const std::string& why) const {
  const std::string range = "an integer >= " + std::to_string(minimum);
  record(key, maximum < 100000000 ? range + " and <= " + std::to_string(maximum) : range, "");
  // A placeholder count: small, allowed (4 points make a cubic spline).
  const json& value = require(key, std::clamp(4, minimum, maximum));
  if (!value.is_number_integer()) fail(key, range);
  // Unsigned values beyond 2^63 (18446744073709551615) are out of range, not negative.
  const bool huge = value.is_number_unsigned() && value.get<unsigned long long>() > 9223372036854775807ull;
  const long long i = huge ? std::numeric_limits<long long>::max() : value.get<long long>();
  if (i < minimum) fail(key, range);
  if (i > maximum) fail(key, range + " and <= " + std::to_string(maximum) + " (" + why + ")");
  return static_cast<int>(i);
}

int Params::integer(const Key& key, int minimum, int maximum, int fallback, const std::string& why) const {
  record(key, "an integer >= " + std::to_string(minimum) + " and <= " + std::to_string(maximum), std::to_string(fallback));
  return has(key) && !absentWhileRecording(obj_, key) ? integer(key, minimum, maximum, why) : fallback;
}

int Params::integer(const Key& key, int minimum, int fallback) const {
  record(key, "an integer >= " + std::to_string(minimum), std::to_string(fallback));
  return has(key) && !absentWhileRecording(obj_, key) ? integer(key, minimum) : fallback;
}

std::string Params::string(const Key& key) const {
  record(key, "a string", "");
  const json& value = require(key, "");
  if (!value.is_string()) fail(key, "a string");
  return value.get<std::string>();
}

std::string Params::string(const Key& key, const std::string& fallback) const {
  record(key, "a string", "\"" + fallback + "\"");
  return has(key) && !absentWhileRecording(obj_, key) ? string(key) : fallback;
}

bool Params::boolean(const Key& key, bool fallback) const {
  record(key, "true or false", fallback ? "true" : "false");
  if (!has(key) || absentWhileRecording(obj_, key)) return fallback;
  const json& value = require(key);
  if (!value.is_boolean()) fail(key, "true or false");
  return value.get<bool>();
}

Vec3 Params::toVec3(const json& value, const std::string& at, const std::string& what) const {
  if (!value.is_array() || value.size() != 3) failAt(at, what, describeJson(value));
  Vec3 out;
  for (int k = 0; k < 3; ++k) {
    // A bad coordinate is reported at its own pointer (".../gravity/2"), with its own value.
    const std::string element = at + "/" + std::to_string(k);
    const std::string coordinate = std::string(1, "xyz"[k]) + " of " + what;
    if (!value[k].is_number()) failAt(element, "a number (" + coordinate + ")", describeJson(value[k]));
    if (!std::isfinite(value[k].get<double>()))
      failAt(element, "a finite number (" + coordinate + ")", describeJson(value[k]));
    out[k] = value[k].get<double>();
  }
  return out;
}

Vec3 Params::vec3(const Key& key) const {
  record(key, "[x, y, z]", "");
  return toVec3(require(key, json::array({1.0, 0.0, 0.0})), pointer(key), "a 3-vector [x, y, z]");
}

Vec3 Params::vec3(const Key& key, const Vec3& fallback) const {
  record(key, "[x, y, z]", vec3Text(fallback));
  return has(key) && !absentWhileRecording(obj_, key) ? vec3(key) : fallback;
}

Points Params::points(const Key& key, int minimum, int maximum, const std::string& why) const {
  record(key, "a list of " + std::to_string(minimum) + " to " + std::to_string(maximum) + " points [x, y, z]", "");
  const json& value = require(key, placeholderPoints(minimum));
  if (value.is_array() && value.size() > static_cast<std::size_t>(maximum))
    fail(key, "a list of at most " + std::to_string(maximum) + " points (" + why + ")",
         "a list of " + std::to_string(value.size()));
  return points(key, minimum);
}

Points Params::points(const Key& key, int minimum) const {
  record(key, "a list of at least " + std::to_string(minimum) + " points [x, y, z]", "");
  const json& value = require(key, placeholderPoints(minimum));
  const std::string what = "a list of at least " + std::to_string(minimum) + " points [x, y, z]";
  if (!value.is_array() || static_cast<int>(value.size()) < minimum) fail(key, what);
  Points out(value.size(), 3);
  for (std::size_t i = 0; i < value.size(); ++i)
    out.row(i) = toVec3(value[i], pointer(key) + "/" + std::to_string(i), "a point [x, y, z]").transpose();
  return out;
}

Params Params::object(const Key& key) const {
  record(key, "an object", "");
  const json& value = require(key, json::object());
  if (!value.is_object()) fail(key, "an object");
  return Params(value, file_, pointer(key), owner_);
}

std::vector<Params> Params::objects(const Key& key) const {
  record(key, "a list of objects", "");
  const json& value = require(key, json::array());
  if (!value.is_array()) fail(key, "an array of objects");
  std::vector<Params> out;
  for (std::size_t i = 0; i < value.size(); ++i) {
    const std::string sub = pointer(key) + "/" + std::to_string(i);
    if (!value[i].is_object()) failAt(sub, "an object", describeJson(value[i]));
    out.emplace_back(value[i], file_, sub, owner_);
  }
  return out;
}

const json& Params::raw(const Key& key) const {
  record(key, "a JSON value (the component's page says which)", "");
  return require(key);
}

void Params::finish() const {
  if (!obj_.is_object()) return;
  for (const auto& item : obj_.items()) {
    if (known_.count(item.key())) continue;
    std::ostringstream known;
    std::string guess;
    for (const auto& k : known_) {
      known << (known.tellp() > 0 ? ", " : "") << k;
      if (guess.empty() && looksLikeMisspelling(item.key(), k)) guess = "did you mean '" + k + "'? ";
    }
    throw SceneError(where(item.key()),
                     "unknown parameter '" + item.key() + "'" + (owner_.empty() ? "" : " of " + owner_) + " (" + guess +
                         "known parameters: " + (known.str().empty() ? "none" : known.str()) + ")");
  }
}

}  // namespace filum
