#include "filum/visual/display_server.hpp"

#include <fcntl.h>
#include <poll.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <mutex>
#include <sstream>
#include <stdexcept>

#if FILUM_WITH_OPENCV
#include <X11/Xlib.h>
#endif

namespace filum::visual {

namespace {

std::mutex mutex;
std::weak_ptr<DisplayServer> current;

#if FILUM_WITH_OPENCV
// Xlib's default error handler ends the process on any protocol error (VTK triggers harmless
// BadWindow errors when a window goes away); report them and carry on instead.
int reportXError(Display* display, XErrorEvent* event) {
  char text[256];
  XGetErrorText(display, event->error_code, text, sizeof text);
  static int reported = 0;
  if (reported++ < 5) std::fprintf(stderr, "filum: X error ignored: %s (request %d)\n", text, event->request_code);
  return 0;
}
#endif

void prepareXlib() {
#if FILUM_WITH_OPENCV
  static std::once_flag once;
  std::call_once(once, [] {
    XInitThreads();  // VTK and Mesa may touch the display from helper threads
    XSetErrorHandler(reportXError);
  });
#endif
}

std::string findOnPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "/usr/bin:/bin");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const std::filesystem::path candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return "";
}

}  // namespace

bool DisplayServer::xvfbInstalled() { return !findOnPath("Xvfb").empty(); }

std::shared_ptr<DisplayServer> DisplayServer::ensure() {
  std::lock_guard<std::mutex> lock(mutex);
  if (auto existing = current.lock()) return existing;
  prepareXlib();
  std::shared_ptr<DisplayServer> server(new DisplayServer());
  const char* display = std::getenv("DISPLAY");
  if (display && *display) {
    server->display_ = display;
    current = server;
    return server;
  }
  const std::string xvfb = findOnPath("Xvfb");
  if (xvfb.empty())
    throw std::runtime_error(
        "no X display: DISPLAY is not set and Xvfb is not installed (install the Debian package xvfb, see "
        "scripts/setup.sh, or run under an X session)");
  // Xvfb writes the display number it chose to the pipe once it accepts connections.
  int fds[2];
  if (::pipe(fds) != 0) throw std::runtime_error("cannot create a pipe to start Xvfb");
  const pid_t parent = ::getpid();
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("cannot fork to start Xvfb");
  if (pid == 0) {
    ::close(fds[0]);
    ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // never outlive the process that started it
    if (::getppid() != parent) ::_exit(1);
    const int null = ::open("/dev/null", O_RDWR);
    if (null >= 0) {
      ::dup2(null, STDIN_FILENO);
      ::dup2(null, STDOUT_FILENO);
      ::dup2(null, STDERR_FILENO);
    }
    const std::string fd = std::to_string(fds[1]);
    ::execl(xvfb.c_str(), "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1080x24", "-nolisten", "tcp",
            static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::close(fds[1]);
  server->pid_ = pid;
  std::string number;
  pollfd wait{fds[0], POLLIN, 0};
  while (true) {
    if (::poll(&wait, 1, 20000) <= 0) break;  // 20 s: Xvfb normally answers in well under a second
    char c;
    if (::read(fds[0], &c, 1) != 1 || c == '\n') break;
    number += c;
  }
  ::close(fds[0]);
  if (number.empty()) {
    // ~DisplayServer stops the process.
    throw std::runtime_error("Xvfb (" + xvfb + ") did not start: no display number within 20 s");
  }
  server->display_ = ":" + number;
  ::setenv("DISPLAY", server->display_.c_str(), 1);
  current = server;
  return server;
}

DisplayServer::~DisplayServer() {
  if (pid_ <= 0) return;
  ::kill(pid_, SIGTERM);
  int status = 0;
  ::waitpid(pid_, &status, 0);
  const char* display = std::getenv("DISPLAY");
  if (display && display_ == display) ::unsetenv("DISPLAY");
}

}  // namespace filum::visual
