// SceneError: every problem with user input names the place (file, JSON path or component),
// what was expected and what was found.
#pragma once

#include <stdexcept>
#include <string>

namespace filum {

class SceneError : public std::runtime_error {
 public:
  /// "<where>: expected <expected>, found <found>".
  SceneError(const std::string& where, const std::string& expected, const std::string& found)
      : std::runtime_error(where + ": expected " + expected + ", found " + found),
        where_(where) {}
  /// "<where>: <message>" for errors that are not a value mismatch.
  SceneError(const std::string& where, const std::string& message)
      : std::runtime_error(where + ": " + message), where_(where) {}

  const std::string& where() const { return where_; }

 private:
  std::string where_;
};

}  // namespace filum
