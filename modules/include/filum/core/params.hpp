// Params: typed, checked access to one JSON object of a scene file. Every failure throws a
// SceneError naming the file, the JSON path (RFC 6901 pointer), what was expected and what was
// found. finish() refuses parameters that nobody read (typos such as "stifness").
#pragma once

#include <deque>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/types.hpp"

namespace filum {

/// Levenshtein distance (insertions, deletions, substitutions): how far a typo is from a name.
std::size_t editDistance(const std::string& a, const std::string& b);

/// One parameter a component's fromParams asked for: its key ("outer/key" inside a nested
/// object), what it must be (the accessor's own check: "a number > 0", "an integer >= 2 and <=
/// 100000"), its default as text ("" when it is required) and the unit the reading code takes
/// it in ("" for counts, names and switches).
struct ParameterRead {
  std::string key, expected, fallback;
  bool required = false;
  std::string unit;
};

/// A parameter's key, and for a quantity the unit the reading code takes its value in, stated
/// where it is read: p.positive({"radius", "m"}). Scene files are in SI units throughout; "1"
/// marks a pure number (a ratio, a friction coefficient, a direction, a colour). `filum list`
/// prints the units from these reads, so the listing is the code's own.
struct Key {
  Key(const char* name) : name(name) {}
  Key(std::string name) : name(std::move(name)) {}
  Key(const char* name, const char* unit) : name(name), unit(unit ? unit : "") {}
  Key(std::string name, const char* unit) : name(std::move(name)), unit(unit ? unit : "") {}
  operator const std::string&() const { return name; }

  std::string name;
  const char* unit = "";
};

/// While one is alive (in this thread), every Params records the parameters it is asked for, and
/// a required parameter that is missing yields a harmless placeholder (a number 1, the smallest
/// allowed count, an empty string or list) instead of an error: a component created from an
/// empty object lists what it reads (`filum list TYPE`), from the code that reads it, so the
/// listing cannot drift from the checks. A creator may still refuse a placeholder (a file name,
/// an enumeration), or two exclusive parameters both "given": `filum list` then tries again with
/// that parameter absent (treatAsAbsent), until the creator runs through or stops going further.
class ParameterRecorder {
 public:
  ParameterRecorder();
  ~ParameterRecorder();
  ParameterRecorder(const ParameterRecorder&) = delete;
  ParameterRecorder& operator=(const ParameterRecorder&) = delete;
  const std::vector<ParameterRead>& reads() const { return reads_; }
  /// The key read last (the one a creator most likely refused, when it threw).
  const std::string& lastKey() const { return last_key_; }
  /// From now on has(key) says no for this key, so that a creator that refused its placeholder
  /// (or refused two exclusive parameters both "given") goes past it on the next try.
  void treatAsAbsent(const std::string& key) { absent_.insert(key); }
  bool treatedAsAbsent(const std::string& key) const { return absent_.count(key) > 0; }

 private:
  friend class Params;
  std::vector<ParameterRead> reads_;
  std::string last_key_;
  std::set<std::string> absent_;
  std::deque<nlohmann::json> placeholders_;  // stable addresses: Params return references to them
  ParameterRecorder* outer_ = nullptr;
};

class Params {
 public:
  /// obj must outlive the Params. file is for messages only; path is obj's JSON pointer.
  Params(const nlohmann::json& obj, std::string file, std::string path, std::string owner = "");

  /// Whether the object holds `key` (a quantity read only when given says its unit here too).
  bool has(const Key& key) const;

  /// Any finite number (units are the caller's; say them in `what`).
  double number(const Key& key) const;
  double number(const Key& key, double fallback) const;
  /// A number > 0.
  double positive(const Key& key) const;
  double positive(const Key& key, double fallback) const;
  /// A number >= 0.
  double nonNegative(const Key& key, double fallback) const;
  /// A curve abscissa in [0, 1] (unit "1").
  double abscissa(const Key& key) const;
  /// An integer >= minimum.
  int integer(const Key& key, int minimum) const;
  int integer(const Key& key, int minimum, int fallback) const;
  /// An integer in [minimum, maximum], checked before the caller allocates anything for it;
  /// `why` says where the maximum comes from (memory, physics) and goes into the message.
  int integer(const Key& key, int minimum, int maximum, const std::string& why) const;
  int integer(const Key& key, int minimum, int maximum, int fallback, const std::string& why) const;
  std::string string(const Key& key) const;
  std::string string(const Key& key, const std::string& fallback) const;
  bool boolean(const Key& key, bool fallback) const;
  /// [x, y, z] of finite numbers.
  Vec3 vec3(const Key& key) const;
  Vec3 vec3(const Key& key, const Vec3& fallback) const;
  /// A list of [x, y, z] with at least `minimum` entries.
  Points points(const Key& key, int minimum) const;
  /// The same with at most `maximum` entries (checked before allocating); `why` as for integer().
  Points points(const Key& key, int minimum, int maximum, const std::string& why) const;

  /// A nested object as Params (the key must hold an object).
  Params object(const Key& key) const;
  /// A nested array of objects.
  std::vector<Params> objects(const Key& key) const;
  /// The raw value (marks the key as read).
  const nlohmann::json& raw(const Key& key) const;

  /// Throws if the object holds a key that no accessor asked for.
  void finish() const;

  /// "file: /json/path/key" of a key (or of this object if key is empty).
  std::string where(const std::string& key = "") const;
  /// Throws SceneError(where(key) + " (owner)", expected, found-value).
  [[noreturn]] void fail(const std::string& key, const std::string& expected) const;
  [[noreturn]] void fail(const std::string& key, const std::string& expected, const std::string& found) const;

  /// A copy whose messages say which component the parameters belong to ("for DynamicSpline").
  Params withOwner(const std::string& owner) const {
    Params copy = *this;
    copy.owner_ = owner;
    return copy;
  }

  const std::string& file() const { return file_; }
  const std::string& path() const { return path_; }

 private:
  const nlohmann::json& require(const std::string& key) const;
  /// require(), with `placeholder` for a missing key while a ParameterRecorder records.
  const nlohmann::json& require(const std::string& key, const nlohmann::json& placeholder) const;
  /// Tells the active ParameterRecorder (if any) that `key` is read: what it must be and its
  /// default ("" and required when it has none), and its unit. The first read of a key wins.
  void record(const Key& key, const std::string& expected, const std::string& fallback) const;
  /// The key as the recorder names it: "outer/key" inside a nested object.
  std::string recordedKey(const std::string& key) const;
  /// "nothing (the parameter is missing)", naming an unread key that looks like a misspelling.
  std::string missing(const std::string& key) const;
  /// The JSON pointer of a key of this object.
  std::string pointer(const std::string& key) const;
  /// Throws SceneError for the value at a full JSON pointer (an element of a list or vector).
  [[noreturn]] void failAt(const std::string& pointer, const std::string& expected, const std::string& found) const;
  Vec3 toVec3(const nlohmann::json& value, const std::string& pointer, const std::string& what) const;

  const nlohmann::json& obj_;
  std::string file_;
  std::string path_;
  std::string owner_;
  mutable std::set<std::string> known_;  // every key asked for, present or not
};

/// A short rendering of a JSON value for messages ("-1", "\"abc\"", "[0, 0, 1]", "an object").
std::string describeJson(const nlohmann::json& value);

/// A key escaped as one RFC 6901 pointer token ("a/b" -> "a~1b").
std::string escapePointer(const std::string& key);

}  // namespace filum
