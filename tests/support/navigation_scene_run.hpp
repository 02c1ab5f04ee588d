// A shipped navigation scene (guidewires, catheters, coils) played as `filum run` plays it: the
// scene and its "navigation" metrics, started before the first step and told of each step after
// it; and how deep an instrument's surface lies in a vessel's wall.
#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/all_components.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/vessel_tree.hpp"
#include "filum/haptics/navigation_metrics.hpp"

namespace filum::test {

struct NavigationSceneRun {
  std::string path;
  nlohmann::json document;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<haptics::NavigationMetrics> metrics;  // nullptr: no "navigation" block

  /// apps/scenes/<file> of the source tree; `edit` changes the document before it is loaded (a
  /// negative control: a path taken out).
  explicit NavigationSceneRun(const std::string& file, const std::function<void(nlohmann::json&)>& edit = {})
      : path(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + file), document(readJsonFile(path)) {
    if (edit) edit(document);
    scene = loadScene(document, path, app::makeFactory());
    metrics = haptics::NavigationMetrics::fromScene(document, path, *scene);
    scene->init();
    if (metrics) metrics->start(*scene);
  }
  /// One step, and the metrics told of it when it succeeded.
  StepReport step() {
    StepReport report = scene->step();
    if (report.ok && metrics) metrics->afterStep(*scene, scene->settings().dt);
    return report;
  }
  long steps() const { return std::lround(scene->settings().duration / scene->settings().dt); }
};

/// How far a body of radius r whose centre line passes where `sample` was taken reaches into the
/// vessel's wall, in units of r (<= 0: clear of it): (r − d)/r, with d = value / |gradient| the
/// distance to the wall of the lumen's field near it (geometry/vessel_tree.hpp).
inline double wallDepth(const geometry::VesselTree::Sample& sample, double r) {
  return (r - sample.value / sample.gradient.norm()) / r;
}

}  // namespace filum::test
