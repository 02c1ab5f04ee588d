#include "filum/run_visual.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "filum/visual/heads_up_display.hpp"
#include "filum/visual/obj_writer.hpp"
#include "filum/visual/ply_writer.hpp"
#include "filum/visual/vtp_writer.hpp"

namespace filum::app {

namespace {
constexpr double kMaxVideoFps = 30.0;  // players choke on higher rates; denser frames play slowed down
}  // namespace

RunVisual::RunVisual(Scene& scene, const nlohmann::json& document, const std::string& directory,
                     const RunVisualOptions& options, double duration, const std::vector<BodyDrawing>& drawings)
    : options_(options), directory_(directory), scene_name_(scene.settings().name), visuals_(scene) {
  for (const BodyDrawing& d : drawings) visuals_.drawBodyWith(*d.body, *d.model, d.name);
  visuals_.update(scene.state());
  // The scene's camera, or one that frames the visual models at t = 0.
  if (auto camera = visual::readCamera(document, scene.settings().source)) {
    camera_ = *camera;
  } else {
    Vec3 lower(-0.05, -0.05, -0.05), upper(0.05, 0.05, 0.05);
    visuals_.bounds(lower, upper);
    camera_ = visual::frameBox(lower, upper);
  }
  if (options_.meshes) {
    std::filesystem::create_directories(directory_ + "/meshes");
    series_ = std::make_unique<visual::PvdSeries>(directory_ + "/meshes.pvd");
  }
  if (options_.render) {
    renderer_ = std::make_unique<visual::OffscreenRenderer>(camera_);
    visual::FrameRecorderOptions recorder;
    recorder.directory = directory_;
    recorder.fps = std::min(kMaxVideoFps, 1.0 / camera_.frame_interval);  // slow motion beyond 30 fps
    recorder.expected_frames = static_cast<int>(std::floor(duration / camera_.frame_interval + 1e-9)) + 1;
    recorder.png_frames = options_.png_frames;
    recorder.title = scene_name_;
    recorder_ = std::make_unique<visual::FrameRecorder>(recorder);
    fluoroscopy_ = visual::FluoroscopyView::fromScene(document, scene.settings().source);
    if (fluoroscopy_) {
      pedal_ = haptics::FluoroscopyPedal::fromScene(document, scene.settings().source);
      Vec3 lower(-0.05, -0.05, -0.05), upper(0.05, 0.05, 0.05);
      visuals_.bounds(lower, upper);
      fluoroscopy_renderer_ = std::make_unique<visual::OffscreenRenderer>(
          fluoroscopy_->camera(fluoroscopy_->isocenter.value_or(0.5 * (lower + upper))));
      const double interval = std::max(camera_.frame_interval, fluoroscopy_->frame_interval);
      recorder.directory = directory_ + "/fluoroscopy";
      recorder.fps = std::min(kMaxVideoFps, 1.0 / interval);
      recorder.expected_frames = static_cast<int>(std::floor(duration / interval + 1e-9)) + 1;
      recorder.title = scene_name_ + " (fluoroscopy)";
      fluoroscopy_recorder_ = std::make_unique<visual::FrameRecorder>(recorder);
      held_ = visual::Image(fluoroscopy_->size, fluoroscopy_->size);
    }
  }
}

RunVisual::~RunVisual() = default;

std::string RunVisual::meshName(std::size_t model, int mesh) const {
  // A model's first mesh carries its name; the others (the strands of a cut thread) a suffix.
  std::string name = visuals_.modelName(model);
  if (mesh > 0) {  // appended piece by piece: GCC 12 sees a false overlap (-Wrestrict) in "_" + temporary
    name += '_';
    name += std::to_string(mesh + 1);
  }
  return name;
}

void RunVisual::writeMeshes(const Scene& scene) {
  if (!options_.meshes) return;
  visuals_.update(scene.state());
  std::vector<std::string> files;
  for (std::size_t i = 0; i < visuals_.models().size(); ++i)
    for (int k = 0; k < visuals_.models()[i]->meshCount(); ++k) {
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_%06d.vtp", mesh_frames_);
      const std::string file = "meshes/" + meshName(i, k) + suffix;
      visual::writeMeshVtp(directory_ + "/" + file, visuals_.models()[i]->mesh(k));
      files.push_back(file);
    }
  series_->addStep(scene.state().time, files);
  ++mesh_frames_;
}

void RunVisual::render(const Scene& scene, double wall_per_simulated_ms, const std::string& footer) {
  if (!options_.render) return;
  visuals_.update(scene.state());
  frame_models_.assign(visuals_.models().begin(), visuals_.models().end());  // (capacity kept between frames)
  for (visual::VisualModel* overlay : overlays_) {
    overlay->update(scene.state());
    frame_models_.push_back(overlay);
  }
  visual::Image frame = renderer_->render(frame_models_);
  if (camera_.heads_up)
    visual::drawHeadsUp(frame, scene_name_ + " | " +
                                   visual::headsUpText(scene.state().time, wall_per_simulated_ms,
                                                       scene.energy(scene.state()).total()));
  if (camera_.heads_up && !footer.empty()) visual::drawFooter(frame, footer);
  recorder_->add(frame, scene.state().time);
  if (fluoroscopy_) renderFluoroscopy(scene);
}

void RunVisual::renderFluoroscopy(const Scene& scene) {
  // Pulses on the grid k · frame_interval, each taken at the camera's frame nearest to it (within
  // half the camera's interval): frames come when the run renders, not at arbitrary times.
  const double t = scene.state().time;
  if (t < next_fluoroscopy_ - 0.5 * camera_.frame_interval) return;
  while (next_fluoroscopy_ <= t + 0.5 * camera_.frame_interval) next_fluoroscopy_ += fluoroscopy_->frame_interval;
  const bool on = pedal_->on(t);
  if (on) {
    held_ = fluoroscopy_->finish(fluoroscopy_renderer_->render(frame_models_, visual::OffscreenRenderer::Style::kXray),
                                 fluoroscopy_frames_);
  }
  visual::Image frame = held_;
  char text[160];
  std::snprintf(text, sizeof text, "%s %.0f  %s %.0f  |  t %.2f s  fluoro %.1f s%s",
                fluoroscopy_->lao_degrees >= 0.0 ? "LAO" : "RAO", std::abs(fluoroscopy_->lao_degrees),
                fluoroscopy_->cranial_degrees >= 0.0 ? "CRA" : "CAU", std::abs(fluoroscopy_->cranial_degrees), t,
                pedal_->time(t), on ? "" : "  (last image hold)");
  visual::drawHeadsUp(frame, text);
  fluoroscopy_recorder_->add(frame, t);
  ++fluoroscopy_frames_;
}

void RunVisual::finish(const Scene& scene) {
  if (finished_) return;
  finished_ = true;
  if (options_.meshes) {
    visuals_.update(scene.state());
    std::vector<visual::NamedMesh> named;
    for (std::size_t i = 0; i < visuals_.models().size(); ++i)
      for (int k = 0; k < visuals_.models()[i]->meshCount(); ++k) {
        const visual::TriangleMesh& mesh = visuals_.models()[i]->mesh(k);
        named.push_back({meshName(i, k), &mesh});
        if (mesh.triangleCount() > 0) visual::writePly(directory_ + "/meshes/final_" + meshName(i, k) + ".ply", mesh);
      }
    visual::writeObj(directory_ + "/meshes/final.obj", named);
  }
  if (recorder_) recorder_->finish();
  if (fluoroscopy_recorder_) fluoroscopy_recorder_->finish();
}

std::string RunVisual::summary() const {
  std::string s;
  if (options_.meshes) s += ", meshes.pvd (" + std::to_string(mesh_frames_) + " frames), meshes/final.obj, meshes/final_*.ply";
  if (options_.render)
    s += ", video.avi (" + std::to_string(recorder_->frames()) + " frames)" + (options_.png_frames ? ", frames/*.png" : "") +
         ", contact_sheet.png";
  if (fluoroscopy_recorder_)
    s += ", fluoroscopy/video.avi (" + std::to_string(fluoroscopy_recorder_->frames()) + " frames), fluoroscopy/contact_sheet.png";
  return s;
}

}  // namespace filum::app
