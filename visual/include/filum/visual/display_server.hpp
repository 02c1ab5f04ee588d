// DisplayServer: an X display for OpenCV's viz module (VTK needs an X server even to render off
// screen) and for the interactive window. If $DISPLAY is set it is used as is; otherwise a
// private Xvfb (Debian package xvfb) is started on a free display number (Xvfb -displayfd picks
// it) and $DISPLAY set to it for this process; the server is stopped (SIGTERM to its process id)
// when the last user releases it, and dies with this process (PR_SET_PDEATHSIG).
#pragma once

#include <memory>
#include <string>

namespace filum::visual {

class DisplayServer {
 public:
  ~DisplayServer();
  DisplayServer(const DisplayServer&) = delete;
  DisplayServer& operator=(const DisplayServer&) = delete;

  /// The display of this process, started if needed. Throws std::runtime_error saying what to
  /// install (xvfb) or set (DISPLAY) when there is none and Xvfb cannot be started.
  static std::shared_ptr<DisplayServer> ensure();
  /// True if an Xvfb executable is on the PATH.
  static bool xvfbInstalled();

  const std::string& display() const { return display_; }
  /// True if this object started the Xvfb (false: $DISPLAY was already set).
  bool started() const { return pid_ > 0; }

 private:
  DisplayServer() = default;
  std::string display_;
  int pid_ = -1;
};

}  // namespace filum::visual
