// Factory: creates components by type name from their scene-file parameters. Each library
// registers its components through one explicit register_components(Factory&) (no static
// initialisation tricks the linker could drop).
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "filum/core/component.hpp"
#include "filum/core/params.hpp"

namespace filum {

class Factory {
 public:
  using Creator = std::function<std::unique_ptr<Component>(const Params&)>;

  /// Registers a component type. summary is one line for `filum list`.
  void add(const std::string& type, const std::string& summary, Creator creator);
  /// Registers a type that was built out, with the CMake option that brings it.
  void addUnavailable(const std::string& type, const std::string& cmake_option);
  /// The type used for a role ("Integrator", "ConstraintSolver") when a scene names none.
  void setDefault(const std::string& role, const std::string& type);
  std::string defaultFor(const std::string& role) const;

  bool knows(const std::string& type) const { return creators_.count(type) > 0; }
  /// Creates and names a component; unknown types get an error listing the known ones.
  std::unique_ptr<Component> create(const std::string& type, const Params& params,
                                    const std::string& type_key_where) const;

  std::vector<std::string> typeNames() const;
  const std::string& summary(const std::string& type) const { return summaries_.at(type); }

 private:
  std::map<std::string, Creator> creators_;
  std::map<std::string, std::string> summaries_;
  std::map<std::string, std::string> unavailable_;
  std::map<std::string, std::string> defaults_;
};

/// Registers the kernel's own components (none that simulate; kept for symmetry).
void registerCoreComponents(Factory& factory);

}  // namespace filum
