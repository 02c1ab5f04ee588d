#include "python_scene.hpp"

#include <chrono>
#include <cmath>
#include <stdexcept>

#include "filum/all_components.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/visual_scene.hpp"

namespace filum::python {

struct PythonScene::Renderer {
  visual::VisualScene visuals;
  std::unique_ptr<visual::OffscreenRenderer> renderer;
  explicit Renderer(Scene& scene) : visuals(scene) {}
};

PythonScene::PythonScene(nlohmann::json document, const std::string& source) : document_(std::move(document)) {
  const Factory factory = app::makeFactory();
  scene_ = loadScene(document_, source, factory);
}

PythonScene::~PythonScene() = default;

void PythonScene::step() {
  const auto start = std::chrono::steady_clock::now();
  const StepReport report = scene_->step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  ++timing_.steps;
  timing_.total += wall;
  timing_.last = wall;
  timing_.max = std::max(timing_.max, wall);
  if (!report.ok)
    throw StepFailure("step " + std::to_string(report.step) + " at t = " + std::to_string(report.time) +
                      " s failed (" + report.culprit + "): " + report.message +
                      "; the scene is back at the state before that step");
}

long PythonScene::run(double duration) {
  if (!(duration >= 0.0) || !std::isfinite(duration))
    throw std::invalid_argument("run(duration): expected a finite duration >= 0 s, found " + std::to_string(duration));
  const long steps = std::lround(duration / scene_->settings().dt);
  for (long i = 0; i < steps; ++i) step();
  return steps;
}

visual::Image PythonScene::render() {
  if (!visual::renderingAvailable()) throw RenderingUnavailable(visual::renderingUnavailableMessage());
  try {
    if (!renderer_) {
      auto r = std::make_unique<Renderer>(*scene_);
      r->visuals.update(scene_->state());
      // The scene's camera, or one that frames the visual models now (as `filum run --render`).
      visual::CameraSettings camera;
      if (auto c = visual::readCamera(document_, scene_->settings().source)) {
        camera = *c;
      } else {
        Vec3 lower(-0.05, -0.05, -0.05), upper(0.05, 0.05, 0.05);
        r->visuals.bounds(lower, upper);
        camera = visual::frameBox(lower, upper);
      }
      r->renderer = std::make_unique<visual::OffscreenRenderer>(camera);
      renderer_ = std::move(r);
    }
    renderer_->visuals.update(scene_->state());
    return renderer_->renderer->render(renderer_->visuals.models());
  } catch (const SceneError&) {
    throw;  // a bad camera block names its place
  } catch (const std::runtime_error& e) {
    renderer_.reset();
    throw RenderingUnavailable(std::string("rendering failed: ") + e.what());
  }
}

}  // namespace filum::python
