// PythonScene: what the Python module's `filum.Scene` holds — the scene, the document it was
// loaded from (its camera block), the wall time of its steps and, once a frame was asked for, the
// renderer. One per Python Scene object, shared (std::shared_ptr) with the Body objects and the
// NumPy views into its state, so that neither outlives it.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"
#include "filum/visual/image.hpp"

namespace filum::python {

/// Wall time of the steps taken through the module (s).
struct StepTiming {
  long steps = 0;
  double total = 0.0;
  double last = 0.0;
  double max = 0.0;
};

class PythonScene {
 public:
  /// Loads and checks the scene; throws SceneError naming the place.
  PythonScene(nlohmann::json document, const std::string& source);
  ~PythonScene();

  Scene& scene() { return *scene_; }
  const Scene& scene() const { return *scene_; }

  /// One step; a failed step (rolled back by the scene) throws StepFailure with its report.
  void step();
  /// Steps until `duration` more seconds are simulated (rounded to whole steps); returns the
  /// number of steps. Stops at the first failed step (StepFailure).
  long run(double duration);
  const StepTiming& timing() const { return timing_; }

  /// The scene's visual models drawn from its camera (or one framing them), at the current state.
  /// Throws RenderingUnavailable when this build or this machine cannot render.
  visual::Image render();

 private:
  struct Renderer;
  nlohmann::json document_;
  std::unique_ptr<Scene> scene_;
  StepTiming timing_;
  std::unique_ptr<Renderer> renderer_;
};

/// A step that failed: the scene rolled back to the state before it.
struct StepFailure : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Rendering cannot be had here: no OpenCV in this build, or no X display.
struct RenderingUnavailable : std::runtime_error {
  using std::runtime_error::runtime_error;
};

}  // namespace filum::python
