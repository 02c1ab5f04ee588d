#include "filum/output_settings.hpp"

#include "filum/core/params.hpp"

namespace filum::app {

OutputSettings readOutputSettings(const nlohmann::json& document, const std::string& source) {
  OutputSettings settings;
  if (!document.contains("output")) return settings;
  const Params top(document, source, "");
  const Params output = top.object("output");
  settings.interval = output.positive({"interval", "s"}, settings.interval);
  settings.curve_samples = output.integer("curve_samples", 2, kMaxCurveSamples, settings.curve_samples,
                                          "a frame writes curve_samples lines per body, 10 MB per body at the limit");
  settings.knots = output.boolean("knots", settings.knots);
  output.finish();
  return settings;
}

}  // namespace filum::app
