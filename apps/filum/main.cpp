// filum — command line tool: run scenes headless, check scene files, list components.
#include <algorithm>
#include <csignal>
#include <iostream>
#include <vector>

#include <CLI/CLI.hpp>

#include "filum/all_components.hpp"
#include "filum/check_command.hpp"
#include "filum/list_command.hpp"
#include "filum/run_command.hpp"
#include "filum/view_command.hpp"

int main(int argc, char** argv) {
  // A file size limit (RLIMIT_FSIZE) makes the kernel send SIGXFSZ, which kills the process by
  // default: ignored, the write fails with EFBIG instead, and `run` exits 4 naming the file.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"filum: real-time simulation of threads, tubes and catheters as dynamic splines"};
  app.require_subcommand(1);

  filum::app::RunOptions run;
  CLI::App* run_cmd = app.add_subcommand("run", "simulate a scene headless and write its data and timing");
  run_cmd->add_option("scene", run.scene, "scene file (JSON, comments allowed), e.g. apps/scenes/hanging_thread.json")
      ->required()
      ->check(CLI::ExistingFile);
  run_cmd->add_option("--duration,-t", run.duration, "simulated time in seconds (default: the scene's \"duration\")")
      ->check(CLI::PositiveNumber);
  run_cmd->add_option("--out,-o", run.out, "output folder (default: out/<scene file name without .json>, e.g. out/hanging_thread)");
  run_cmd->add_option("--every", run.interval, "simulated seconds between written frames (default: scene output.interval or 0.01)")
      ->check(CLI::PositiveNumber);
  run_cmd->add_option("--samples", run.curve_samples, "points per curve in curve.csv and the .vtp files (default 64)")
      ->check(CLI::Range(2, 100000));
  bool quiet = false;
  run_cmd->add_flag("--quiet,-q", quiet, "no progress line");
  run_cmd->add_flag("--meshes", run.meshes,
                    "also write the visual meshes: meshes.pvd with meshes/*.vtp (ParaView), meshes/final.obj and "
                    "meshes/final_*.ply (Blender)");
  run_cmd->add_flag("--render", run.render,
                    "also render pictures from the scene's camera: frames/*.png, video.avi, contact_sheet.png "
                    "(needs FILUM_WITH_OPENCV; starts Xvfb when DISPLAY is unset)");
  bool no_png = false;
  run_cmd->add_flag("--no-png", no_png, "with --render: only the video and the contact sheet, no PNG per frame");
  run_cmd->footer(
      "Writes control_points.csv, curve.csv, energy.csv, knot.csv, vtk/*.vtp with curve.pvd (open in ParaView) and "
      "timing.json; with instruments metrics.csv and metrics.json; with --meshes and --render also the meshes, frames, video and contact sheet.\nExit status: 0 done, 2 bad scene, 3 diverged (state rolled back, frames kept), 4 output error, 130 stopped by Ctrl-C (a run with a haptic device: forces off, outputs kept).");

  filum::app::ViewOptions view;
  CLI::App* view_cmd = app.add_subcommand("view", "play a scene in a window in real time; the mouse is a probe");
  view_cmd->add_option("scene", view.scene, "scene file")->required()->check(CLI::ExistingFile);
  view_cmd->add_option("--frames", view.frames, "stop after this many frames (default: until the window is closed)")
      ->check(CLI::NonNegativeNumber);
  view_cmd->add_option("--speed", view.speed, "simulated seconds per wall second (default 1: real time)")
      ->check(CLI::PositiveNumber);
  view_cmd->add_option("--probe-radius", view.probe_radius, "radius of the mouse probe in m (default: 2 % of the "
                                                             "camera distance)")
      ->check(CLI::PositiveNumber);
  view_cmd->add_option("--screenshot", view.screenshot, "write the last frame to this PNG file");
  view_cmd->footer(
      "Mouse: left drag pushes the thread with a sphere; Shift+left drag (or g, then left drag) grabs the nearest "
      "point and pulls it; right drag orbits the camera; the wheel zooms.\nKeys: space pause, r restart, g grab "
      "mode, q or Escape quit; with instruments, 1-9 give one to the mouse (left drag moves it), 0 the probe, c/o "
      "close/open its jaws, [/] turn the needle it holds about the needle's centre. Needs a display (or Xvfb) and "
      "FILUM_WITH_OPENCV.");

  std::vector<std::string> check_scenes;
  CLI::App* check_cmd = app.add_subcommand("check", "load and check scene files without simulating them");
  check_cmd->add_option("scenes", check_scenes, "scene files: one line each, \"<file>: ok (...)\" or \"error: <file>: ...\"; after ok, indented: "
                       "each body's length, radius and mass, and the stiffest mode's period against dt")
      ->required();
  check_cmd->footer("Exit status: 0 all good, 2 some scene refused.");

  std::string list_type;
  CLI::App* list_cmd = app.add_subcommand("list", "list the component types this build knows, or one type's parameters");
  list_cmd->add_option("type", list_type, "a component type: its parameters, required or with their defaults, and their checks");

  CLI11_PARSE(app, argc, argv);

  if (*run_cmd) {
    run.progress = !quiet;
    run.png_frames = !no_png;
    return filum::app::runScene(run, std::cout, std::cerr);
  }
  if (*view_cmd) return filum::app::viewScene(view, std::cerr);
  if (*check_cmd) {
    int status = 0;
    for (const std::string& scene : check_scenes) {
      status = std::max(status, filum::app::checkScene(scene, std::cout));
      std::cout.flush();  // one complete line per scene, even if a later one brought the process down
    }
    return status;
  }
  if (*list_cmd) {
    const filum::Factory factory = filum::app::makeFactory();
    if (list_type.empty()) return filum::app::listTypes(factory, std::cout);
    return filum::app::listParameters(factory, list_type, std::cout, std::cerr);
  }
  return 0;
}
