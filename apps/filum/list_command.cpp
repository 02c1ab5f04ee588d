#include "filum/list_command.hpp"

#include <algorithm>
#include <exception>
#include <ostream>

#include <nlohmann/json.hpp>

#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::app {

int listTypes(const Factory& factory, std::ostream& out) {
  for (const auto& type : factory.typeNames()) out << type << "\t" << factory.summary(type) << '\n';
  out << "(filum list TYPE: that type's parameters)\n";
  return 0;
}

int listParameters(const Factory& factory, const std::string& type, std::ostream& out, std::ostream& err) {
  if (!factory.knows(type)) {
    try {  // the loader's refusal: built out, or the closest known type
      factory.create(type, Params(nlohmann::json::object(), "filum list", ""), "filum list");
    } catch (const SceneError& e) {
      err << "error: " << e.what() << '\n';
    }
    return 2;
  }
  // The component created from an empty object, recording every parameter it asks for; when it
  // refuses a placeholder, again with that parameter absent, until it runs through or stops
  // getting further (each try reads at least the parameters before the refused one again).
  const nlohmann::json empty = nlohmann::json::object();
  ParameterRecorder recorder;
  std::string stopped;
  for (int attempt = 0; attempt < 64; ++attempt) {
    try {
      factory.create(type, Params(empty, "filum list", ""), "filum list");
      stopped.clear();
      break;
    } catch (const std::exception& e) {
      stopped = e.what();
    }
    const std::string refused = recorder.lastKey();
    if (refused.empty() || recorder.treatedAsAbsent(refused)) break;
    recorder.treatAsAbsent(refused);
  }
  out << type << ": " << factory.summary(type) << "\n\n";
  std::size_t width = 9;
  for (const ParameterRead& r : recorder.reads()) width = std::max(width, r.key.size());
  out << "  " << std::string("parameter") << std::string(width - 9 + 2, ' ') << "default   what it must be\n";
  for (const ParameterRead& r : recorder.reads()) {
    out << "  " << r.key << std::string(width - r.key.size() + 2, ' ');
    const std::string fallback = r.required ? "required" : r.fallback;
    out << fallback << std::string(fallback.size() < 10 ? 10 - fallback.size() : 1, ' ');
    out << (r.expected.empty() ? "read when given (see the README's tables)" : r.expected) << '\n';
  }
  if (recorder.reads().empty()) out << "  (no parameters)\n";
  // Read by the scene loader for every component (scene_loader.cpp), not by the component.
  out << "  name" << std::string(width - 4 + 2, ' ') << "the type  a string: its name in messages, outputs and references\n";
  out << "  object" << std::string(width - 6 + 2, ' ')
      << "\"\"        a node path: the body it acts on, when not its own node's\n";
  if (!stopped.empty())
    out << "\nThe list may stop short where the component needs a real value to go on (its other\n"
           "parameters depend on it); with the placeholders it said: "
        << stopped << '\n';
  out << "\n\"-\": no default (given or not, as the component's checks say).\n";
  out << "\nUnits are SI (m, kg, s, N, Pa) unless the README's tables say otherwise.\n";
  return 0;
}

}  // namespace filum::app
