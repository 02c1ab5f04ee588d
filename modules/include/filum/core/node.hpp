// Node: the scene graph. A node owns components and child nodes; a body is a node holding a
// MechanicalState and the force fields and constraints that act on it.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/core/component.hpp"

namespace filum {

class MechanicalState;

class Node {
 public:
  explicit Node(std::string name, Node* parent = nullptr);

  const std::string& name() const { return name_; }
  Node* parent() const { return parent_; }

  /// Path from the root, e.g. "thread/collision"; the root's path is "".
  std::string path() const;

  Node& addChild(std::string name);
  Component& addComponent(std::unique_ptr<Component> component);

  const std::vector<std::unique_ptr<Node>>& children() const { return children_; }
  const std::vector<std::unique_ptr<Component>>& components() const { return components_; }

  /// The node at a relative path ("a/b"), or nullptr.
  Node* find(const std::string& relative_path);

  /// The mechanical state held by this node, or nullptr.
  MechanicalState* mechanicalState() const;

  /// Every component of type T in this node and, if recursive, its descendants (depth first,
  /// in declaration order — the order is part of the determinism contract).
  template <class T>
  void collect(std::vector<T*>& out, bool recursive = true) const {
    for (const auto& c : components_)
      if (auto* t = dynamic_cast<T*>(c.get())) out.push_back(t);
    if (recursive)
      for (const auto& child : children_) child->collect(out, true);
  }

  /// Paths of this node and all descendants (for "known nodes" lists in errors).
  void listPaths(std::vector<std::string>& out) const;

 private:
  std::string name_;
  Node* parent_;
  std::vector<std::unique_ptr<Node>> children_;
  std::vector<std::unique_ptr<Component>> components_;
};

}  // namespace filum
