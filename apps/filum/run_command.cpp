#include "filum/run_command.hpp"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <vector>

#include "filum/all_components.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/run_output.hpp"
#include "filum/run_visual.hpp"
#include "filum/timing_summary.hpp"

namespace filum::app {

namespace {

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

struct OutputSettings {
  double interval = 0.01;
  int curve_samples = 64;
};

/// The scene file's "output" block, checked like every other parameter.
OutputSettings readOutputSettings(const nlohmann::json& document, const std::string& source) {
  OutputSettings settings;
  if (!document.contains("output")) return settings;
  const Params top(document, source, "");
  const Params output = top.object("output");
  settings.interval = output.positive("interval", settings.interval);
  settings.curve_samples = output.integer("curve_samples", 2, settings.curve_samples);
  output.finish();
  return settings;
}

void writeSummary(const std::string& directory, const TimingSummary& timing, std::ostream& log) {
  std::ofstream(directory + "/timing.json") << timing.json();
  log << timing.text();
}

}  // namespace

int runScene(const RunOptions& options, std::ostream& log, std::ostream& progress) {
  const auto start = Clock::now();
  std::unique_ptr<Scene> scene;
  OutputSettings output;
  nlohmann::json document;
  try {
    document = readJsonFile(options.scene);
    output = readOutputSettings(document, options.scene);
    scene = loadScene(document, options.scene, makeFactory());
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  }
  const double dt = scene->settings().dt;
  const double duration = options.duration.value_or(scene->settings().duration);
  const double interval = options.interval.value_or(output.interval);
  const int samples = options.curve_samples.value_or(output.curve_samples);
  if (!(duration > 0.0) || !(interval > 0.0) || samples < 2) {
    log << "error: --duration and --every must be positive and --samples at least 2\n";
    return kRunSceneError;
  }
  const std::string directory =
      options.out.empty() ? "out/" + std::filesystem::path(options.scene).stem().string() : options.out;

  // Visual outputs (on request): bind the visual models, open the renderer.
  std::unique_ptr<RunVisual> visuals;
  if (options.meshes || options.render) {
    try {
      visuals = std::make_unique<RunVisual>(*scene, document, directory,
                                            RunVisualOptions{options.meshes, options.render, options.png_frames}, duration);
    } catch (const SceneError& e) {
      log << "error: " << e.what() << '\n';
      return kRunSceneError;
    } catch (const std::exception& e) {
      log << "error: " << (options.render ? "--render: " : "--meshes: ") << e.what() << '\n';
      return kRunIoError;
    }
  }

  const long steps = std::lround(duration / dt);
  const long frame_every = std::max(1L, std::lround(interval / dt));
  const long render_every = visuals ? std::max(1L, std::lround(visuals->renderInterval() / dt)) : 0;
  double render_wall = 0.0;  // step wall time since the last rendered frame (s)
  std::vector<double> step_seconds;
  step_seconds.reserve(steps);
  log << "scene '" << scene->settings().name << "': " << scene->bodies().size() << " bodies, "
      << scene->dofPointCount() << " control points, " << scene->constraints().size() << " constraints, "
      << scene->integrator().typeName() << ", dt = " << dt << " s, " << steps << " steps -> " << directory << '\n';

  try {
    RunOutput out(directory, samples);
    out.writeFrame(*scene);
    if (visuals) {
      visuals->writeMeshes(*scene);
      visuals->render(*scene, -1.0);
    }
    auto last_progress = start;
    for (long k = 1; k <= steps; ++k) {
      const auto before = Clock::now();
      const StepReport report = scene->step();
      const auto after = Clock::now();
      if (!report.ok) {
        log << "error: " << report.message << '\n'
            << "the " << out.frames() << " frames written so far in " << directory << " are intact\n";
        if (visuals) visuals->finish(*scene);
        writeSummary(directory, TimingSummary::fromStepTimes(step_seconds, dt, seconds(after - start)), log);
        return kRunDiverged;
      }
      step_seconds.push_back(seconds(after - before));
      render_wall += seconds(after - before);
      if (k % frame_every == 0 || k == steps) {
        out.writeFrame(*scene);
        if (visuals) visuals->writeMeshes(*scene);
      }
      if (visuals && (k % render_every == 0 || k == steps)) {
        const long since = k % render_every == 0 ? render_every : k % render_every;
        visuals->render(*scene, render_wall / (since * dt));  // wall ms per simulated ms
        render_wall = 0.0;
      }
      if (options.progress && seconds(after - start) > 3.0 && seconds(after - last_progress) >= 1.0) {
        last_progress = after;
        const double done = static_cast<double>(k) / steps;
        const double elapsed = seconds(after - start);
        progress << "  t = " << scene->state().time << " s of " << duration << " (" << std::lround(100 * done)
                 << "%), " << elapsed << " s elapsed, about " << std::lround(elapsed * (1 - done) / done)
                 << " s left\n";
      }
    }
    if (visuals) visuals->finish(*scene);
    log << "wrote " << out.frames() << " frames to " << directory
        << " (control_points.csv, curve.csv, energy.csv, curve.pvd, timing.json" << (visuals ? visuals->summary() : "")
        << ")\n";
  } catch (const std::exception& e) {
    log << "error: " << e.what() << '\n';
    return kRunIoError;
  }
  writeSummary(directory, TimingSummary::fromStepTimes(step_seconds, dt, seconds(Clock::now() - start)), log);
  return kRunOk;
}

}  // namespace filum::app
