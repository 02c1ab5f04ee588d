// `filum run`: loads a scene, simulates it headless and writes its data and timing summary.
#pragma once

#include <iosfwd>
#include <optional>
#include <string>

namespace filum::app {

struct RunOptions {
  std::string scene;                 // scene file
  std::optional<double> duration;    // s; default: the scene's "duration"
  std::string out;                   // output folder; default: out/<scene file stem>
  std::optional<double> interval;    // s between frames; default: scene "output.interval" or 0.01
  std::optional<int> curve_samples;  // points per curve in curve.csv / .vtp; default 64
  bool progress = true;              // a progress line on stderr for runs longer than 3 s
  bool meshes = false;               // meshes.pvd + meshes/*.vtp, final OBJ and PLY (run_visual.hpp)
  bool render = false;               // frames/*.png, video.avi, contact_sheet.png (run_visual.hpp)
  bool png_frames = true;            // with render: every frame as a PNG too
};

/// Exit codes of `filum run`.
/// kRunInterrupted: Ctrl-C (or SIGTERM) during a run with a haptic device, which stops after its
/// step with the forces off (128 + SIGINT, the shell's convention).
enum RunStatus { kRunOk = 0, kRunSceneError = 2, kRunDiverged = 3, kRunIoError = 4, kRunInterrupted = 130 };

/// Runs the scene; messages go to `log` (stdout) and progress to `progress` (stderr).
int runScene(const RunOptions& options, std::ostream& log, std::ostream& progress);

}  // namespace filum::app
