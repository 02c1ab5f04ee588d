// The shape of a JSON text, checked by one SAX pass before it is parsed into a document:
//  - nesting depth: arrays and objects at most kMaxJsonDepth deep. nlohmann's SAX parser keeps
//    its own stack, but building, copying and describing a document recurse once per level, so
//    100,000 nested brackets overflowed the thread's stack; scenes nest about 8 deep;
//  - duplicate keys: JSON leaves them undefined and nlohmann keeps the last one silently, so a
//    second "count" would override the first without a word. Both places are named.
//  - syntax errors, and numbers beyond the range of a double (1e999), which nlohmann refuses:
//    placed by line, column and the JSON pointer of the value being read.
#pragma once

#include <string>

namespace filum {

/// Deepest nesting of arrays and objects accepted in a scene file (the top-level object is 1).
inline constexpr int kMaxJsonDepth = 64;

/// Throws SceneError "<source>:<line>:<column>: <pointer>: expected ..., found ..." at the first
/// value nested deeper than kMaxJsonDepth, the first key repeated in its object, or the first
/// syntax error ("<source>:<line>:<column>: invalid JSON: ...").
void checkJsonShape(const std::string& text, const std::string& source);

/// 1-based line and column of a byte offset of `text`.
void lineAndColumn(const std::string& text, std::size_t byte, int& line, int& column);

}  // namespace filum
