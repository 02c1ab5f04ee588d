#include "filum/run_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <thread>
#include <vector>

#include "filum/all_components.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/haptic_session.hpp"
#include "filum/haptics/hub_device.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/haptics/navigation_metrics.hpp"
#include "filum/output_settings.hpp"
#include "filum/physics_check.hpp"
#include "filum/run_output.hpp"
#include "filum/run_visual.hpp"
#include "filum/timing_summary.hpp"
#include "filum/visual/instrument_visual.hpp"
#include "filum/visual/needle_visual.hpp"
#include "filum/visual/wound_visual.hpp"
#include "filum/visual/interactive_probe.hpp"

namespace filum::app {

namespace {

// A run that fails before this many steps is most likely set up wrong (dt, integrator, units):
// the error says so (earlyFailureHint).
constexpr long kEarlySteps = 10;

using Clock = std::chrono::steady_clock;

double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }

void writeSummary(const std::string& directory, const TimingSummary& timing, std::ostream& log) {
  const std::string path = directory + "/timing.json";
  std::ofstream out(path);
  out << timing.json();
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed (disk full or file size limit?)");
  log << timing.text();
}

// The command line's overrides, checked against the scene's limits (scene.hpp): the message
// names the scene's dt, which a --duration shorter than dt / 2 or too long for it contradicts.
std::string checkOverrides(const RunOptions& options, const Scene& scene, double duration) {
  const std::string steps = stepCountProblem(duration, scene.settings().dt);
  if (steps.empty()) return "";
  return options.scene + ": /dt (with --duration " + describeJson(duration) + "): expected a run of 1 to " +
         std::to_string(kMaxSteps) + " steps of dt = " + describeJson(scene.settings().dt) + " s, found " + steps;
}

/// metrics.json written (with the last frame's knots when the run's output exists), the metrics
/// and the instruments' events logged.
void finishInstruments(haptics::InstrumentSet& instruments, const RunOutput* output, const std::string& directory,
                       std::ostream& log) {
  instruments.finish();  // devices' forces off
  log << instruments.writeDeviceLogs(directory);
  instruments.writeSummary(directory + "/metrics.json", output ? output->knotSummary() : nlohmann::json());
  for (const std::string& e : instruments.events()) log << "  " << e << '\n';
  log << instruments.metrics().text();
  if (instruments.wound()) log << instruments.wound()->text();
  if (output && !output->knotText().empty()) log << "  knots: " << output->knotText() << '\n';
  log << "  -> metrics.csv, metrics.json\n";
}

/// The threads that tore (ForceField::tearsAt), one line each; the instruments' events list them too.
void logRuptures(const Scene& scene, std::ostream& log) {
  for (const Scene::Rupture& r : scene.ruptures())
    log << "  t = " << r.time << " s: " << r.body << " tore at s = " << r.abscissa << " under " << r.tension << " N\n";
}

/// Forces off, haptics.csv written, the servo's summary logged.
void finishHaptics(haptics::HapticSession& haptic, const std::string& directory, std::ostream& log) {
  haptic.finish();
  haptic.writeCsv(directory + "/haptics.csv");
  log << haptic.summary() << " -> haptics.csv\n";
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
  } catch (const std::exception& e) {  // a check missing in the loader: still the file, never an abort
    log << "error: " << options.scene << ": cannot load the scene: " << e.what() << '\n';
    return kRunSceneError;
  }
  const double dt = scene->settings().dt;
  const double duration = options.duration.value_or(scene->settings().duration);
  const double interval = options.interval.value_or(output.interval);
  const int samples = options.curve_samples.value_or(output.curve_samples);
  if (!(duration > 0.0) || !(interval > 0.0) || samples < 2 || samples > kMaxCurveSamples) {
    log << "error: --duration and --every must be positive and --samples in [2, " << kMaxCurveSamples << "]\n";
    return kRunSceneError;
  }
  if (const std::string problem = checkOverrides(options, *scene, duration); !problem.empty()) {
    log << "error: " << problem << '\n';
    return kRunSceneError;
  }
  const std::string directory =
      options.out.empty() ? "out/" + std::filesystem::path(options.scene).stem().string() : options.out;

  // A haptic device on an instrument's hub (the navigation block's "device"): the hand pushes and
  // turns the instrument and feels it (haptics/hub_device.hpp). Read first: a scene with a
  // "haptics" block too is refused before either device is opened.
  std::unique_ptr<haptics::HubDevice> hub_device;
  try {
    hub_device = haptics::HubDevice::fromScene(document, options.scene, *scene, duration);
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  } catch (const std::exception& e) {
    log << "error: " << options.scene << ": /navigation/device: " << e.what() << '\n';
    return kRunSceneError;
  }
  // A haptic device and its tool (the scene's "haptics" block): the servo loop runs beside the
  // steps (haptics/haptic_session.hpp).
  std::unique_ptr<haptics::HapticSession> haptic;
  try {
    haptic = haptics::HapticSession::fromScene(document, options.scene, *scene, duration);
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  } catch (const std::exception& e) {
    log << "error: " << options.scene << ": /haptics: " << e.what() << '\n';
    return kRunSceneError;
  }

  // The instruments (the scene's "instruments" list): their parts and holds join the scene, their
  // jaws act between the steps (haptics/instrument_set.hpp).
  std::unique_ptr<haptics::InstrumentSet> instruments;
  try {
    instruments = haptics::InstrumentSet::fromScene(document, options.scene, *scene, duration);
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  } catch (const std::exception& e) {
    log << "error: " << options.scene << ": /instruments: " << e.what() << '\n';
    return kRunSceneError;
  }

  // The navigation metrics (the scene's "navigation" block: catheters and guidewires in a lumen).
  std::unique_ptr<haptics::NavigationMetrics> navigation;
  try {
    navigation = haptics::NavigationMetrics::fromScene(document, options.scene, *scene);
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  } catch (const std::exception& e) {
    log << "error: " << options.scene << ": /navigation: " << e.what() << '\n';
    return kRunSceneError;
  }
  if (navigation && instruments) {
    log << "error: " << options.scene << ": /navigation: expected either laparoscopic \"instruments\" or a catheter "
        << "\"navigation\" block (both write metrics.csv), found both\n";
    return kRunSceneError;
  }

  // Visual outputs (on request): bind the visual models, open the renderer. The models the scene
  // file cannot name outlive the visuals that point at them.
  std::vector<std::unique_ptr<visual::WoundVisual>> wound_visuals;  // a wound's lips, drawn as slabs
  std::vector<RunVisual::BodyDrawing> drawings;
  if (instruments && instruments->wound())
    for (int lip = 0; lip < 2; ++lip) {
      wound_visuals.push_back(std::make_unique<visual::WoundVisual>(*instruments->wound(), lip));
      drawings.push_back({&instruments->wound()->lip(lip), wound_visuals.back().get(), "wound_lip_" + std::to_string(lip)});
    }
  std::unique_ptr<RunVisual> visuals;
  if (options.meshes || options.render) {
    try {
      visuals = std::make_unique<RunVisual>(*scene, document, directory,
                                            RunVisualOptions{options.meshes, options.render, options.png_frames}, duration,
                                            drawings);
    } catch (const SceneError& e) {
      log << "error: " << e.what() << '\n';
      return kRunSceneError;
    } catch (const std::exception& e) {
      log << "error: " << (options.render ? "--render: " : "--meshes: ") << e.what() << '\n';
      return kRunIoError;
    }
  }

  // The haptic tool's sphere in the pictures (green while its jaws hold the thread).
  std::unique_ptr<visual::ProbeVisual> tool_visual;
  if (haptic && visuals) {
    tool_visual = std::make_unique<visual::ProbeVisual>(haptic->sharedTool());
    visuals->addOverlay(*tool_visual);
  }
  // The instruments as drawn: shaft and jaws of each.
  std::vector<std::unique_ptr<visual::InstrumentVisual>> instrument_visuals;
  std::vector<std::unique_ptr<visual::NeedleVisual>> needle_visuals;
  if (instruments && visuals) {
    for (int i = 0; i < instruments->size(); ++i)
      for (auto part : {visual::InstrumentVisual::Part::kShaft, visual::InstrumentVisual::Part::kJaws}) {
        instrument_visuals.push_back(std::make_unique<visual::InstrumentVisual>(instruments->instrument(i), part));
        visuals->addOverlay(*instrument_visuals.back());
      }
    for (int k = 0; k < instruments->needleCount(); ++k) {
      needle_visuals.push_back(std::make_unique<visual::NeedleVisual>(instruments->needle(k)));
      visuals->addOverlay(*needle_visuals.back());
    }
  }

  const long steps = std::lround(duration / dt);
  const long frame_every = std::max(1L, std::lround(interval / dt));
  const long render_every = visuals ? std::max(1L, std::lround(visuals->renderInterval() / dt)) : 0;
  double render_wall = 0.0;  // step wall time since the last rendered frame (s)
  std::vector<double> step_seconds;
  step_seconds.reserve(std::min(steps, 1L << 20));  // steps <= kMaxSteps; grows past 8 MB only if the run does
  log << "scene '" << scene->settings().name << "': " << scene->bodies().size() << " bodies, "
      << scene->dofPointCount() << " control points, " << scene->constraints().size() << " constraints, "
      << scene->integrator().typeName() << ", dt = " << dt << " s, " << steps << " steps -> " << directory << '\n';

  std::unique_ptr<RunOutput> output_files;
  // Timing of the steps so far, with what the contact solves did.
  auto summary = [&]() {
    TimingSummary timing = TimingSummary::fromStepTimes(step_seconds, dt, seconds(Clock::now() - start));
    if (const ConstraintSolver* solver = scene->constraintSolver()) timing.contact = solver->contactTally();
    timing.stages = scene->stageTimes();
    return timing;
  };
  // metrics.json written, the navigation metrics logged.
  auto finishNavigation = [&]() {
    if (!navigation) return;
    navigation->writeSummary(directory + "/metrics.json");
    log << navigation->text() << "  -> metrics.csv, metrics.json\n";
  };
  // Forces off, haptics.csv written, the hub device's summary logged.
  auto finishHubDevice = [&]() {
    if (!hub_device) return;
    hub_device->finish();
    hub_device->writeCsv(directory + "/haptics.csv");
    log << hub_device->summary() << " -> haptics.csv\n";
  };
  // The run stops: what happened, the frames kept, the summary (exit 3).
  auto diverged = [&](const std::string& message) {
    if (haptic) finishHaptics(*haptic, directory, log);
    finishHubDevice();
    finishNavigation();
    if (instruments) finishInstruments(*instruments, output_files.get(), directory, log);
    else logRuptures(*scene, log);
    log << "error: " << message << '\n';
    // Rolled back to the last good state: its step count is the failed step's index.
    if (scene->state().steps < kEarlySteps) log << earlyFailureHint(*scene) << '\n';
    log << "the " << (output_files ? output_files->frames() : 0) << " frames written so far in " << directory
        << " are intact\n";
    if (visuals) visuals->finish(*scene);
    writeSummary(directory, summary(), log);
    return kRunDiverged;
  };
  try {
    output_files = std::make_unique<RunOutput>(directory, samples, output.knots);
    RunOutput& out = *output_files;
    if (instruments) instruments->openCsv(directory + "/metrics.csv");
    if (navigation) {
      navigation->openCsv(directory + "/metrics.csv");
      navigation->start(*scene);
    }
    out.writeFrame(*scene);
    if (visuals) {
      visuals->writeMeshes(*scene);
      visuals->render(*scene, -1.0, out.knotText());
    }
    auto last_progress = start;
    if (haptic) haptic->start();
    if (hub_device) hub_device->start();
    if (instruments) instruments->start();
    const auto haptic_start = Clock::now();
    for (long k = 1; k <= steps; ++k) {
      // A device on the wall clock: the simulation keeps pace with it (never ahead of it).
      if ((haptic && haptic->threaded()) || (instruments && instruments->threaded()) ||
          (hub_device && hub_device->threaded()))
        std::this_thread::sleep_until(haptic_start + std::chrono::duration_cast<Clock::duration>(
                                                         std::chrono::duration<double>(scene->state().time)));
      if (haptic) haptic->beforeStep(*scene);
      if (hub_device) hub_device->beforeStep(*scene);
      const auto before = Clock::now();
      if (instruments) instruments->beforeStep(*scene);
      const StepReport report = scene->step();
      if (instruments && report.ok) instruments->afterStep(*scene);
      if (navigation && report.ok) navigation->afterStep(*scene, dt);
      const auto after = Clock::now();
      if (!report.ok) return diverged(report.message);
      if (haptic) haptic->afterStep(*scene);
      if (hub_device) hub_device->afterStep(*scene);
      if ((haptic && haptic->interrupted()) || (instruments && instruments->interrupted()) ||
          (hub_device && hub_device->interrupted())) {
        if (haptic) finishHaptics(*haptic, directory, log);
        finishHubDevice();
        finishNavigation();
        if (instruments) finishInstruments(*instruments, output_files.get(), directory, log);
        log << "interrupted (Ctrl-C) at t = " << scene->state().time << " s: forces off\n";
        if (visuals) visuals->finish(*scene);
        writeSummary(directory, summary(), log);
        return kRunInterrupted;
      }
      step_seconds.push_back(seconds(after - before));
      render_wall += seconds(after - before);
      if (k % frame_every == 0 || k == steps) {
        out.writeFrame(*scene);
        if (visuals) visuals->writeMeshes(*scene);
      }
      if (visuals && (k % render_every == 0 || k == steps)) {
        const long since = k % render_every == 0 ? render_every : k % render_every;
        visuals->render(*scene, render_wall / (since * dt), out.knotText());  // wall ms per simulated ms
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
    if (haptic) finishHaptics(*haptic, directory, log);
    finishHubDevice();
    finishNavigation();
    if (instruments) finishInstruments(*instruments, output_files.get(), directory, log);
    else logRuptures(*scene, log);
    if (visuals) visuals->finish(*scene);
    log << "wrote " << out.frames() << " frames to " << directory
        << " (control_points.csv, curve.csv, energy.csv, " << (output.knots ? "knot.csv, " : "")
        << (scene->layoutControllers().empty() ? "" : "layout.csv, ") << "curve.pvd, timing.json"
        << (visuals ? visuals->summary() : "") << ")\n";
    if (!scene->layoutControllers().empty())
      log << "adaptive refinement: " << scene->adaptiveInsertions() << " control points inserted, "
          << scene->adaptiveRemovals() << " removed\n";
    writeSummary(directory, summary(), log);
  } catch (const NonFiniteFrame& e) {
    // A finite state whose curve or energy overflows: nothing of the frame was written.
    try {
      return diverged(scene->settings().source + ": " + e.what());
    } catch (const std::exception& io) {
      log << "error: " << io.what() << '\n';
      return kRunIoError;
    }
  } catch (const std::exception& e) {
    log << "error: " << e.what() << '\n';
    return kRunIoError;
  }
  return kRunOk;
}

}  // namespace filum::app
