#include "filum/list_command.hpp"

#include <algorithm>
#include <exception>
#include <ostream>

#include <nlohmann/json.hpp>

#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::app {
namespace {

/// Columns a UTF-8 string takes (units have "³", "·", "°"): its bytes that do not continue a character.
std::size_t displayWidth(const std::string& text) {
  std::size_t columns = 0;
  for (const char ch : text) columns += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
  return columns;
}

}  // namespace

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
  // Columns at least two spaces apart: parameter, default, unit, what it must be.
  std::size_t width = 9, default_width = 8, unit_width = 4;
  for (const ParameterRead& r : recorder.reads()) {
    width = std::max(width, r.key.size());
    default_width = std::max(default_width, displayWidth(r.required ? "required" : r.fallback));
    unit_width = std::max(unit_width, displayWidth(r.unit));
  }
  const auto row = [&](const std::string& key, const std::string& fallback, const std::string& unit,
                       const std::string& what) {
    out << "  " << key << std::string(width - key.size() + 2, ' ');
    out << fallback << std::string(default_width - displayWidth(fallback) + 2, ' ');
    out << unit << std::string(unit_width - displayWidth(unit) + 2, ' ') << what << '\n';
  };
  row("parameter", "default", "unit", "what it must be");
  for (const ParameterRead& r : recorder.reads())
    row(r.key, r.required ? "required" : r.fallback, r.unit,
        r.expected.empty() ? "read when given (see the README's tables)" : r.expected);
  if (recorder.reads().empty()) out << "  (no parameters)\n";
  // Read by the scene loader for every component (scene_loader.cpp), not by the component.
  row("name", "the type", "", "a string: its name in messages, outputs and references");
  row("object", "\"\"", "", "a node path: the body it acts on, when not its own node's");
  if (!stopped.empty())
    out << "\nThe list may stop short where the component needs a real value to go on (its other\n"
           "parameters depend on it); with the placeholders it said: "
        << stopped << '\n';
  out << "\n\"-\": no default (given or not, as the component's checks say).\n";
  out << "Units: SI, as everywhere in a scene file; 1: a pure number (a ratio, a coefficient, an\n"
         "abscissa in [0, 1]); blank: not a quantity (a count, a name, a choice).\n";
  return 0;
}

}  // namespace filum::app
