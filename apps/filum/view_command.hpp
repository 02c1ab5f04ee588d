// `filum view`: plays a scene in a window in real time (where a display exists; under Xvfb for
// tests) and lets the mouse act as a probe, the stand-in for the haptic device:
//   left button      press on or near a thread and drag: a sphere pushes it;
//   Shift + left     (or key g to toggle grab mode) grab the nearest point and pull it;
//   right button     drag to orbit the camera around its look-at point; wheel: zoom;
//   space            pause / resume;   r: restart;   q or Escape: quit.
// The probe moves in the plane facing the camera at the depth of the thread point nearest to the
// pointer when the button went down. Frames are rendered off screen (OffscreenRenderer) and
// shown in a plain X11 window (ViewerWindow); the simulation advances by the wall time elapsed
// between frames (capped, so a scene slower than real time plays slower, as the heads-up line
// says).
#pragma once

#include <functional>
#include <iosfwd>
#include <optional>
#include <string>

#include "filum/core/scene.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/interactive_probe.hpp"
#include "filum/visual/viewer_window.hpp"

namespace filum::app {

struct ViewFrame {
  int index;                                // frame number, from 0
  visual::ViewerWindow& window;
  const Scene& scene;
  const visual::CameraSettings& camera;
  const haptics::ToolState& probe;
  const haptics::InstrumentSet* instruments;  // the scene's "instruments" (null without)
  int selected;                               // the instrument the mouse drives (−1: the probe)
  const std::string& heads_up;                // the frame's heads-up line, as drawn
};

struct ViewOptions {
  std::string scene;
  int frames = 0;                      // stop after this many frames (0: until the window closes)
  double speed = 1.0;                  // simulated seconds per wall second
  std::optional<double> fixed_step;    // simulated seconds per frame instead of wall time (tests)
  std::optional<double> probe_radius;  // m; default 2 % of the camera distance
  std::string screenshot;              // PNG of the last frame, if set
  std::function<void(const ViewFrame&)> on_frame;  // called after each frame is shown (tests, scripts)
};

/// Exit status: 0 closed normally, 2 bad scene, 4 no display or no OpenCV.
int viewScene(const ViewOptions& options, std::ostream& log);

}  // namespace filum::app
