// RunVisual: the visual outputs of `filum run`, on request:
//   --meshes   meshes/<model>_NNNNNN.vtp with meshes.pvd (every output frame; ParaView plays the
//              skinned threads, spheres and organ meshes), and at the end meshes/final.obj (all
//              models as named objects) and meshes/final_<model>.ply (Blender, MeshLab);
//   --render   frames/frame_NNNNNN.png, video.avi (Motion-JPEG, real-time playback) and
//              contact_sheet.png, pictures from the scene's "camera" (or a camera framing the
//              scene at t = 0), with a heads-up line: simulated time, wall time per simulated
//              millisecond and energy; with a "fluoroscopy" block in the scene, also
//              fluoroscopy/video.avi and fluoroscopy/contact_sheet.png: the C-arm's view
//              (visual/fluoroscopy_view.hpp) at its pulse rate (at most as often as the camera's
//              frames), holding the last image while the pedal is up, with the fluoroscopy time.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"
#include "filum/haptics/fluoroscopy_pedal.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/fluoroscopy_view.hpp"
#include "filum/visual/frame_recorder.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/pvd_series.hpp"
#include "filum/visual/visual_scene.hpp"

namespace filum::app {

struct RunVisualOptions {
  bool meshes = false;
  bool render = false;
  bool png_frames = true;  // with render: every frame as PNG too
};

class RunVisual {
 public:
  /// A body drawn by a model the scene file cannot name (a wound's lip as its slab) instead of its
  /// default skin, in pictures and meshes (visual::VisualScene::drawBodyWith); the model must
  /// outlive the RunVisual.
  struct BodyDrawing {
    const MechanicalState* body;
    visual::VisualModel* model;
    std::string name;
  };

  /// Binds the visual models (throws SceneError), draws the bodies of `drawings` by their models,
  /// frames the camera on them all when the scene has none, and opens the renderer (throws
  /// std::runtime_error, e.g. without OpenCV or an X display). `duration` (s) spreads the
  /// contact sheet.
  RunVisual(Scene& scene, const nlohmann::json& document, const std::string& directory,
            const RunVisualOptions& options, double duration, const std::vector<BodyDrawing>& drawings = {});
  ~RunVisual();

  bool active() const { return options_.meshes || options_.render; }
  /// Simulated seconds between rendered frames (the camera's frame_interval).
  double renderInterval() const { return camera_.frame_interval; }
  const visual::CameraSettings& camera() const { return camera_; }

  /// Writes the meshes of the scene's current state (an output frame).
  void writeMeshes(const Scene& scene);
  /// Renders the current state; wall_per_simulated_ms < 0 when unknown (first frame). A non-empty
  /// `footer` is drawn on a band at the bottom (the knots of the last output frame).
  void render(const Scene& scene, double wall_per_simulated_ms, const std::string& footer = {});
  /// Draws `model` too in the pictures (not in the meshes): a model that is not a scene
  /// component, such as the haptic tool's sphere. It must outlive this object.
  void addOverlay(visual::VisualModel& model) { overlays_.push_back(&model); }
  /// Final OBJ/PLY, video and contact sheet (idempotent).
  void finish(const Scene& scene);
  /// What was written, for the log ("meshes.pvd, video.avi, ...").
  std::string summary() const;

 private:
  /// The file name of mesh `mesh` of visual model `model`: its name, then _2, _3... for the
  /// meshes after the first (the strands of a cut thread).
  std::string meshName(std::size_t model, int mesh) const;
  /// The fluoroscopy frame of the current state (or the held one while the pedal is up).
  void renderFluoroscopy(const Scene& scene);
  RunVisualOptions options_;
  std::string directory_;
  std::string scene_name_;
  visual::VisualScene visuals_;
  visual::CameraSettings camera_;
  std::unique_ptr<visual::PvdSeries> series_;
  std::unique_ptr<visual::OffscreenRenderer> renderer_;
  std::unique_ptr<visual::FrameRecorder> recorder_;
  std::vector<visual::VisualModel*> overlays_;
  std::vector<visual::VisualModel*> frame_models_;  // the scene's models and the overlays, per frame
  std::optional<visual::FluoroscopyView> fluoroscopy_;
  std::unique_ptr<haptics::FluoroscopyPedal> pedal_;
  std::unique_ptr<visual::OffscreenRenderer> fluoroscopy_renderer_;  // its own window and camera
  std::unique_ptr<visual::FrameRecorder> fluoroscopy_recorder_;
  visual::Image held_;  // the last image taken (black before the first)
  double next_fluoroscopy_ = 0.0;
  int fluoroscopy_frames_ = 0;
  int mesh_frames_ = 0;
  bool finished_ = false;
};

}  // namespace filum::app
