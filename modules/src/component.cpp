#include "filum/core/component.hpp"

namespace filum {

std::string Component::describe() const {
  std::string text = "'" + name_ + "' (" + typeName() + ")";
  if (!origin_.empty()) text += " at " + origin_;
  return text;
}

}  // namespace filum
