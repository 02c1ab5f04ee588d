#include "filum/core/json_shape.hpp"

#include <iterator>
#include <map>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace filum {

using nlohmann::json;

namespace {

// A character iterator that publishes how far the parser has read, so that the SAX events
// (which carry no position) can be placed: at a key, the lexer has just read its closing quote;
// at '[' or '{', the bracket itself.
class TrackingIterator {
 public:
  using iterator_category = std::input_iterator_tag;
  using value_type = char;
  using difference_type = std::ptrdiff_t;
  using pointer = const char*;
  using reference = const char&;

  TrackingIterator(const char* at, const char** read) : at_(at), read_(read) {}
  reference operator*() const { return *at_; }
  TrackingIterator& operator++() {
    *read_ = ++at_;
    return *this;
  }
  TrackingIterator operator++(int) {
    TrackingIterator before = *this;
    ++*this;
    return before;
  }
  bool operator==(const TrackingIterator& other) const { return at_ == other.at_; }
  bool operator!=(const TrackingIterator& other) const { return at_ != other.at_; }

 private:
  const char* at_;
  const char** read_;
};

class ShapeChecker final : public json::json_sax_t {
 public:
  ShapeChecker(const std::string& text, const std::string& source) : text_(text), source_(source) {}
  const char* read_ = nullptr;  // one past the last character the lexer read

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(json::number_integer_t) override { return value(); }
  bool number_unsigned(json::number_unsigned_t) override { return value(); }
  bool number_float(json::number_float_t, const json::string_t&) override { return value(); }
  bool string(json::string_t&) override { return value(); }
  bool binary(json::binary_t&) override { return value(); }
  bool start_object(std::size_t) override { return open(false); }
  bool start_array(std::size_t) override { return open(true); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }
  bool key(json::string_t& key) override {
    Frame& frame = frames_.back();
    frame.key = key;
    const std::size_t at = offset(key.size() + 1);  // the opening quote
    const auto [first, inserted] = frame.keys.emplace(key, at);
    if (!inserted) duplicate(first->second, at);
    return true;
  }
  bool parse_error(std::size_t position, const std::string& token, const nlohmann::detail::exception& e) override {
    const std::size_t at = position > 0 ? position - 1 : 0;  // position: characters read
    if (e.id == 406) {
      // A number beyond the range of a double (json::out_of_range 406): the lexer stops at its
      // last character; point at its first.
      throw SceneError(place(at + 1 > token.size() ? at + 1 - token.size() : 0) + ": " + pointer(frames_.size()),
                       "a finite number", token + ", which is beyond the range of a double (about 1.8e308)");
    }
    throw SceneError(place(at), std::string("invalid JSON: ") + e.what());
  }

 private:
  struct Frame {
    bool array;
    std::size_t index = 0;               // of the next element, in an array
    std::string key;                     // of the current member, in an object
    std::map<std::string, std::size_t> keys;  // members so far and where their keys start
  };

  std::size_t offset(std::size_t back = 0) const {
    const std::size_t read = static_cast<std::size_t>(read_ - text_.data());
    return read > back ? read - back - 1 : 0;
  }
  std::string place(std::size_t at) const {
    int line = 0, column = 0;
    lineAndColumn(text_, at, line, column);
    return source_ + ":" + std::to_string(line) + ":" + std::to_string(column);
  }
  // The pointer of the current value, up to `frames` levels.
  std::string pointer(std::size_t frames) const {
    std::string out;
    for (std::size_t k = 0; k < frames && k < frames_.size(); ++k)
    {
      // Appended piece by piece: GCC 12 sees a false overlap (-Wrestrict) in "/" + temporary.
      out += '/';
      out += frames_[k].array ? std::to_string(frames_[k].index) : escapePointer(frames_[k].key);
    }
    return out.empty() ? "/" : out;
  }
  bool open(bool array) {
    if (static_cast<int>(frames_.size()) >= kMaxJsonDepth) tooDeep(offset());
    frames_.push_back(Frame{array, 0, {}, {}});
    return true;
  }
  bool close() {
    frames_.pop_back();
    return value();
  }
  bool value() {
    if (!frames_.empty() && frames_.back().array) ++frames_.back().index;
    return true;
  }
  [[noreturn]] void duplicate(std::size_t first, std::size_t again) const {
    int line = 0, column = 0;
    lineAndColumn(text_, first, line, column);
    throw SceneError(place(again) + ": " + pointer(frames_.size()),
                     "each key once in an object (JSON leaves a repeated key undefined)",
                     "'" + frames_.back().key + "' again; it was first given at line " + std::to_string(line) +
                         ", column " + std::to_string(column));
  }
  // Named by the deepest object member that holds the too-deep value: the field the user wrote.
  [[noreturn]] void tooDeep(std::size_t at) const {
    std::size_t member = 0;
    for (std::size_t k = 0; k < frames_.size(); ++k)
      if (!frames_[k].array) member = k + 1;
    throw SceneError(place(at) + ": " + pointer(member),
                     "arrays and objects nested at most " + std::to_string(kMaxJsonDepth) +
                         " deep (the readers recurse once per level; scenes nest about 8 deep)",
                     "a value nested deeper than that");
  }

  const std::string& text_;
  const std::string& source_;
  std::vector<Frame> frames_;
};

}  // namespace

void lineAndColumn(const std::string& text, std::size_t byte, int& line, int& column) {
  line = 1;
  column = 1;
  for (std::size_t i = 0; i < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
}

void checkJsonShape(const std::string& text, const std::string& source) {
  ShapeChecker checker(text, source);
  checker.read_ = text.data();
  const char* end = text.data() + text.size();
  json::sax_parse(TrackingIterator(text.data(), &checker.read_), TrackingIterator(end, &checker.read_), &checker,
                  json::input_format_t::json, /*strict=*/true, /*ignore_comments=*/true);
}

}  // namespace filum
