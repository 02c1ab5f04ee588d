// Component: the unit a scene is assembled from (paper's three-sided model: mechanical,
// collision and visual sides, joined by mappings; docs/architecture.md, "The three-sided model").
#pragma once

#include <string>

namespace filum {

class Node;

/// Base of every scene component. A component is created by the Factory from its JSON
/// parameters, owned by a Node, and initialised once by Scene::init().
class Component {
 public:
  virtual ~Component() = default;

  /// The registered type name, e.g. "DynamicSpline".
  virtual std::string typeName() const = 0;

  const std::string& name() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }

  /// Where the component was declared (file and JSON path), for error messages.
  const std::string& origin() const { return origin_; }
  void setOrigin(std::string origin) { origin_ = std::move(origin); }

  /// The node that owns this component (set when it is added to a node).
  Node* node() const { return node_; }
  void setNode(Node* node) { node_ = node; }

  /// "'name' (Type) at origin", used in every message about this component.
  std::string describe() const;

 private:
  std::string name_;
  std::string origin_;
  Node* node_ = nullptr;
};

}  // namespace filum
