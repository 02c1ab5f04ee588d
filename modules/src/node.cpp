#include "filum/core/node.hpp"

#include "filum/core/mechanical_state.hpp"

namespace filum {

Node::Node(std::string name, Node* parent) : name_(std::move(name)), parent_(parent) {}

std::string Node::path() const {
  if (!parent_) return "";
  const std::string up = parent_->path();
  return up.empty() ? name_ : up + "/" + name_;
}

Node& Node::addChild(std::string name) {
  children_.push_back(std::make_unique<Node>(std::move(name), this));
  return *children_.back();
}

Component& Node::addComponent(std::unique_ptr<Component> component) {
  component->setNode(this);
  components_.push_back(std::move(component));
  return *components_.back();
}

Node* Node::find(const std::string& relative_path) {
  if (relative_path.empty()) return this;
  const auto slash = relative_path.find('/');
  const std::string head = relative_path.substr(0, slash);
  const std::string rest = slash == std::string::npos ? "" : relative_path.substr(slash + 1);
  for (auto& child : children_)
    if (child->name() == head) return child->find(rest);
  return nullptr;
}

MechanicalState* Node::mechanicalState() const {
  for (const auto& c : components_)
    if (auto* m = dynamic_cast<MechanicalState*>(c.get())) return m;
  return nullptr;
}

void Node::listPaths(std::vector<std::string>& out) const {
  if (parent_) out.push_back(path());
  for (const auto& child : children_) child->listPaths(out);
}

}  // namespace filum
