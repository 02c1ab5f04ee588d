// ViewerWindow: the window of `filum view` — a plain X11 (Xlib) window that shows the frames of
// the off-screen renderer and reports mouse and keyboard events. The frames are drawn by
// OffscreenRenderer (OpenCV viz) and copied in with XPutImage; viz's own interactive window is
// not used because its event loop (Viz3d::spinOnce) proved unreliable (see
// offscreen_renderer.hpp), and because here the left mouse button must move the probe, not the
// camera. Needs FILUM_WITH_OPENCV=ON (it links Xlib with the renderer) and an X display.
#pragma once

#include <memory>
#include <string>

#include "filum/visual/image.hpp"

namespace filum::visual {

struct WindowEvent {
  enum class Type { kNone, kButtonPress, kButtonRelease, kMotion, kKey, kClose };
  Type type = Type::kNone;
  int x = 0, y = 0;     // pointer position (pixels, y down)
  int button = 0;       // 1 left, 2 middle, 3 right, 4/5 wheel
  bool shift = false;   // Shift held
  std::string key;      // X keysym name for kKey ("space", "g", "q", "Escape", ...)
};

class ViewerWindow {
 public:
  /// Opens a width × height window titled `title` on the display (DisplayServer). Throws
  /// std::runtime_error without OpenCV/X11 or a display.
  ViewerWindow(int width, int height, const std::string& title);
  ~ViewerWindow();
  ViewerWindow(const ViewerWindow&) = delete;
  ViewerWindow& operator=(const ViewerWindow&) = delete;

  /// Shows a frame (same size as the window).
  void show(const Image& frame);
  /// The next pending event, without waiting; false if there is none.
  bool poll(WindowEvent& event);
  /// Sends an event to this window through the X server (XSendEvent), as if the user had made
  /// it: for tests and scripted demonstrations.
  void sendToSelf(const WindowEvent& event);
  /// True when the server (not only this process) shows the window as mapped.
  bool mapped() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace filum::visual
