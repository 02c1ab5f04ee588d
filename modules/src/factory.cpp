#include "filum/core/factory.hpp"

#include <cctype>

#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace filum {

void Factory::add(const std::string& type, const std::string& summary, Creator creator) {
  creators_[type] = std::move(creator);
  summaries_[type] = summary;
  unavailable_.erase(type);
}

void Factory::addUnavailable(const std::string& type, const std::string& cmake_option) {
  if (!creators_.count(type)) unavailable_[type] = cmake_option;
}

void Factory::setDefault(const std::string& role, const std::string& type) { defaults_[role] = type; }

std::string Factory::defaultFor(const std::string& role) const {
  const auto it = defaults_.find(role);
  return it == defaults_.end() ? "" : it->second;
}

std::vector<std::string> Factory::typeNames() const {
  std::vector<std::string> names;
  for (const auto& [type, creator] : creators_) names.push_back(type);
  return names;
}

std::unique_ptr<Component> Factory::create(const std::string& type, const Params& params,
                                           const std::string& type_key_where) const {
  const auto it = creators_.find(type);
  if (it == creators_.end()) {
    const auto off = unavailable_.find(type);
    if (off != unavailable_.end())
      throw SceneError(type_key_where, "component type '" + type + "' was built out; reconfigure with -D" +
                                           off->second + "=ON to bring it");
    std::string known, guess;
    std::size_t closest = 3;  // a suggestion only within two edits (or a difference of case alone)
    for (const auto& name : typeNames()) {
      known += (known.empty() ? "" : ", ") + name;
      std::string lower_type = type, lower_name = name;
      for (char& ch : lower_type) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      for (char& ch : lower_name) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
      const std::size_t distance = lower_type == lower_name ? 0 : editDistance(type, name);
      if (distance < closest) {
        closest = distance;
        guess = name;
      }
    }
    std::string found = "\"";
    found += type;
    found += '"';
    if (!guess.empty()) {
      found += " (did you mean \"";
      found += guess;
      found += "\"?)";
    }
    throw SceneError(type_key_where, "a known component type (" + known + ")", found);
  }
  std::unique_ptr<Component> component = it->second(params);
  params.finish();
  return component;
}

void registerCoreComponents(Factory& /*factory*/) {}

}  // namespace filum
