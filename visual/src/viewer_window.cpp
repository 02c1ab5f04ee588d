#include "filum/visual/viewer_window.hpp"

#include <cstring>
#include <stdexcept>

#include "filum/visual/display_server.hpp"
#include "filum/visual/offscreen_renderer.hpp"

#if FILUM_WITH_OPENCV
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#endif

namespace filum::visual {

#if FILUM_WITH_OPENCV

struct ViewerWindow::Impl {
  std::shared_ptr<DisplayServer> server;
  Display* display = nullptr;
  Window window = 0;
  GC gc = nullptr;
  Visual* visual = nullptr;
  int depth = 0;
  int width = 0, height = 0;
  Atom delete_message = 0;
  std::vector<char> pixels;  // 32 bits per pixel for XPutImage

  ~Impl() {
    if (display) {
      if (gc) XFreeGC(display, gc);
      if (window) XDestroyWindow(display, window);
      XCloseDisplay(display);
    }
  }
};

ViewerWindow::ViewerWindow(int width, int height, const std::string& title) : impl_(std::make_unique<Impl>()) {
  Impl& w = *impl_;
  w.server = DisplayServer::ensure();
  w.display = XOpenDisplay(w.server->display().c_str());
  if (!w.display) throw std::runtime_error("cannot open the X display " + w.server->display());
  const int screen = DefaultScreen(w.display);
  XVisualInfo info;
  if (!XMatchVisualInfo(w.display, screen, 24, TrueColor, &info))
    throw std::runtime_error("the X display " + w.server->display() + " has no 24-bit TrueColor visual");
  w.visual = info.visual;
  w.depth = info.depth;
  w.width = width;
  w.height = height;
  XSetWindowAttributes attributes{};
  attributes.colormap = XCreateColormap(w.display, RootWindow(w.display, screen), w.visual, AllocNone);
  attributes.event_mask = ExposureMask | ButtonPressMask | ButtonReleaseMask | PointerMotionMask | KeyPressMask |
                          StructureNotifyMask;
  w.window = XCreateWindow(w.display, RootWindow(w.display, screen), 0, 0, width, height, 0, w.depth, InputOutput,
                           w.visual, CWColormap | CWEventMask | CWBorderPixel, &attributes);
  XStoreName(w.display, w.window, title.c_str());
  // A fixed size: the frames are rendered at the camera's size.
  XSizeHints hints{};
  hints.flags = PMinSize | PMaxSize;
  hints.min_width = hints.max_width = width;
  hints.min_height = hints.max_height = height;
  XSetWMNormalHints(w.display, w.window, &hints);
  w.delete_message = XInternAtom(w.display, "WM_DELETE_WINDOW", False);
  XSetWMProtocols(w.display, w.window, &w.delete_message, 1);
  w.gc = XCreateGC(w.display, w.window, 0, nullptr);
  XMapWindow(w.display, w.window);
  XSync(w.display, False);
  w.pixels.resize(static_cast<std::size_t>(4) * width * height);
}

ViewerWindow::~ViewerWindow() = default;

void ViewerWindow::show(const Image& frame) {
  Impl& w = *impl_;
  if (frame.width != w.width || frame.height != w.height)
    throw std::runtime_error("ViewerWindow::show: the frame size differs from the window's");
  // BGR → the visual's 32-bit pixels (masks are 0xff0000, 0xff00, 0xff on every common server).
  const auto shift = [](unsigned long mask) {
    int s = 0;
    while (mask && !(mask & 1)) mask >>= 1, ++s;
    return s;
  };
  const int rs = shift(w.visual->red_mask), gs = shift(w.visual->green_mask), bs = shift(w.visual->blue_mask);
  auto* out = reinterpret_cast<std::uint32_t*>(w.pixels.data());
  for (std::size_t i = 0, n = static_cast<std::size_t>(w.width) * w.height; i < n; ++i)
    out[i] = (std::uint32_t(frame.bgr[3 * i + 2]) << rs) | (std::uint32_t(frame.bgr[3 * i + 1]) << gs) |
             (std::uint32_t(frame.bgr[3 * i]) << bs);
  XImage* image = XCreateImage(w.display, w.visual, w.depth, ZPixmap, 0, w.pixels.data(), w.width, w.height, 32, 0);
  if (!image) throw std::runtime_error("XCreateImage failed");
  XPutImage(w.display, w.window, w.gc, image, 0, 0, 0, 0, w.width, w.height);
  image->data = nullptr;  // owned by pixels, not by the XImage
  XDestroyImage(image);
  XFlush(w.display);
}

bool ViewerWindow::poll(WindowEvent& event) {
  Impl& w = *impl_;
  while (XPending(w.display) > 0) {
    XEvent e;
    XNextEvent(w.display, &e);
    event = WindowEvent{};
    switch (e.type) {
      case ButtonPress:
      case ButtonRelease:
        event.type = e.type == ButtonPress ? WindowEvent::Type::kButtonPress : WindowEvent::Type::kButtonRelease;
        event.x = e.xbutton.x;
        event.y = e.xbutton.y;
        event.button = static_cast<int>(e.xbutton.button);
        event.shift = (e.xbutton.state & ShiftMask) != 0;
        return true;
      case MotionNotify:
        event.type = WindowEvent::Type::kMotion;
        event.x = e.xmotion.x;
        event.y = e.xmotion.y;
        event.shift = (e.xmotion.state & ShiftMask) != 0;
        return true;
      case KeyPress: {
        event.type = WindowEvent::Type::kKey;
        const KeySym sym = XLookupKeysym(&e.xkey, 0);
        const char* name = XKeysymToString(sym);
        event.key = name ? name : "";
        event.shift = (e.xkey.state & ShiftMask) != 0;
        return true;
      }
      case ClientMessage:
        if (static_cast<Atom>(e.xclient.data.l[0]) == w.delete_message) {
          event.type = WindowEvent::Type::kClose;
          return true;
        }
        break;
      default:
        break;  // Expose: the next frame repaints anyway
    }
  }
  return false;
}

void ViewerWindow::sendToSelf(const WindowEvent& event) {
  Impl& w = *impl_;
  XEvent e{};
  long mask = 0;
  switch (event.type) {
    case WindowEvent::Type::kButtonPress:
    case WindowEvent::Type::kButtonRelease:
      e.type = event.type == WindowEvent::Type::kButtonPress ? ButtonPress : ButtonRelease;
      e.xbutton.display = w.display;
      e.xbutton.window = w.window;
      e.xbutton.x = event.x;
      e.xbutton.y = event.y;
      e.xbutton.button = static_cast<unsigned>(event.button);
      e.xbutton.state = event.shift ? ShiftMask : 0;
      e.xbutton.same_screen = True;
      mask = e.type == ButtonPress ? ButtonPressMask : ButtonReleaseMask;
      break;
    case WindowEvent::Type::kMotion:
      e.type = MotionNotify;
      e.xmotion.display = w.display;
      e.xmotion.window = w.window;
      e.xmotion.x = event.x;
      e.xmotion.y = event.y;
      e.xmotion.state = (event.shift ? ShiftMask : 0) | Button1Mask;
      e.xmotion.same_screen = True;
      mask = PointerMotionMask;
      break;
    case WindowEvent::Type::kKey:
      e.type = KeyPress;
      e.xkey.display = w.display;
      e.xkey.window = w.window;
      e.xkey.keycode = XKeysymToKeycode(w.display, XStringToKeysym(event.key.c_str()));
      e.xkey.state = event.shift ? ShiftMask : 0;
      e.xkey.same_screen = True;
      mask = KeyPressMask;
      break;
    case WindowEvent::Type::kClose:
      e.type = ClientMessage;
      e.xclient.window = w.window;
      e.xclient.message_type = XInternAtom(w.display, "WM_PROTOCOLS", False);
      e.xclient.format = 32;
      e.xclient.data.l[0] = static_cast<long>(w.delete_message);
      mask = NoEventMask;
      break;
    case WindowEvent::Type::kNone:
      return;
  }
  XSendEvent(w.display, w.window, False, mask, &e);
  // Round trip: the server has queued the event on this same connection before it answers, so
  // the next poll() sees it.
  XSync(w.display, False);
}

bool ViewerWindow::mapped() const {
  XWindowAttributes attributes;
  return XGetWindowAttributes(impl_->display, impl_->window, &attributes) && attributes.map_state == IsViewable;
}

#else

struct ViewerWindow::Impl {};
ViewerWindow::ViewerWindow(int, int, const std::string&) { throw std::runtime_error(renderingUnavailableMessage()); }
ViewerWindow::~ViewerWindow() = default;
void ViewerWindow::show(const Image&) {}
bool ViewerWindow::poll(WindowEvent&) { return false; }
void ViewerWindow::sendToSelf(const WindowEvent&) {}
bool ViewerWindow::mapped() const { return false; }

#endif

}  // namespace filum::visual
