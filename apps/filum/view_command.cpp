#include "filum/view_command.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <ostream>
#include <sstream>

#include <Eigen/Geometry>

#include "filum/all_components.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/haptics/fluoroscopy_pedal.hpp"
#include "filum/haptics/haptic_session.hpp"
#include "filum/haptics/hub_control.hpp"
#include "filum/haptics/instrument_set.hpp"
#include "filum/haptics/hub_device.hpp"
#include "filum/haptics/navigation_metrics.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/run_command.hpp"
#include "filum/visual/fluoroscopy_view.hpp"
#include "filum/visual/heads_up_display.hpp"
#include "filum/visual/image_file.hpp"
#include "filum/visual/instrument_visual.hpp"
#include "filum/visual/needle_visual.hpp"
#include "filum/visual/wound_visual.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/visual_scene.hpp"

namespace filum::app {

namespace {

using Clock = std::chrono::steady_clock;

/// Gives every curve body of the loaded scene the interaction tool's force field, the mouse's
/// probe (the scene file is not touched), and binds the scene again.
void attachProbe(Scene& scene, const std::shared_ptr<haptics::ToolState>& probe) {
  for (MechanicalState* body : scene.bodies()) {
    if (!body->curve()) continue;
    auto field = std::make_unique<haptics::ToolForceField>(probe);
    field->setName("mouse probe");
    field->setOrigin(body->origin() + " (mouse probe of filum view)");
    body->node()->addComponent(std::move(field));
  }
  scene.init();
}

/// The depth (along the view) of the spline point whose projection is nearest to pixel (u, v).
double pickDepth(const Scene& scene, const visual::CameraSettings& camera, double u, double v) {
  double best = std::numeric_limits<double>::infinity(), depth = (camera.look_at - camera.position).norm();
  for (const MechanicalState* body : scene.bodies()) {
    const auto* spline = body->curve();
    if (!spline) continue;
    const ConstPointsMap q = body->block(scene.state().q);
    for (int k = 0; k <= 200; ++k) {
      const Vec3 x = geometry::curvePoint(spline->basis(), q, k / 200.0);
      const visual::Pixel p = visual::project(camera, x);
      const double d = std::hypot(p.u - u, p.v - v);
      if (p.depth > 0.0 && d < best) {
        best = d;
        depth = p.depth;
      }
    }
  }
  return depth;
}

/// Orbits the camera about its look-at point: yaw about the up axis, pitch about the right axis.
void orbit(visual::CameraSettings& camera, double yaw, double pitch) {
  const Vec3 offset = camera.position - camera.look_at;
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(yaw, camera.up.normalized()) * Eigen::AngleAxisd(pitch, camera.right()))
                                .toRotationMatrix();
  const Vec3 rotated = R * offset;
  if (rotated.normalized().cross(camera.up.normalized()).norm() > 0.05) camera.position = camera.look_at + rotated;
}

// A hub whose constraint let go (released, cut) leaves the keys; the arrows stay on the hub they
// drove, or, when it was that one, pass to the next (after the last: to the one before).
void dropHub(std::vector<std::unique_ptr<haptics::HubControl>>& hubs, std::size_t index, std::size_t& keyed,
             const SceneError& error, std::ostream& log) {
  log << "filum view: the hub of '" << hubs[index]->name() << "' cannot be moved any more: " << error.what() << '\n';
  hubs.erase(hubs.begin() + static_cast<std::ptrdiff_t>(index));
  if (keyed > index || keyed == hubs.size()) keyed = keyed > 0 ? keyed - 1 : 0;
}

}  // namespace

int viewScene(const ViewOptions& options, std::ostream& log) {
  if (!visual::renderingAvailable()) {
    log << "error: filum view: " << visual::renderingUnavailableMessage() << '\n';
    return kRunIoError;
  }
  // The scene, with the mouse probe's force on every curve body: the tool of the scene's
  // "haptics" block (its coupling gains, radius and capture; its device stays idle) or, without
  // one, a probe whose gains are the explicit step's caps (haptics/tool.hpp).
  std::shared_ptr<haptics::ToolState> probe;
  std::unique_ptr<haptics::HapticSession> haptic;
  std::unique_ptr<haptics::InstrumentSet> instruments;  // on their scripts until a key gives one to the mouse
  std::unique_ptr<Scene> scene;
  std::vector<std::unique_ptr<haptics::HubControl>> hubs;  // arrows: push, pull and turn a hub
  std::size_t hub_index = 0;                              // the one the arrows drive (Tab: the next)
  std::unique_ptr<haptics::HubDevice> hub_device;     // or a haptic device at the hub (then no arrows)
  bool hub_lost_logged = false;
  std::unique_ptr<haptics::FluoroscopyPedal> pedal;   // f: the X-ray pedal
  std::optional<visual::FluoroscopyView> fluoroscopy; // x: the fluoroscope's monitor instead of the 3D view
  nlohmann::json document;
  double capture_factor = 3.0;  // capture distance / probe radius
  try {
    document = readJsonFile(options.scene);
    scene = loadScene(document, options.scene, makeFactory());
    hub_device = haptics::HubDevice::fromScene(document, options.scene, *scene, 1.0);  // (before: one device)
    if (hub_device) hub_device->start();
    haptic = haptics::HapticSession::fromScene(document, options.scene, *scene, 1.0);
    if (haptic) {
      probe = haptic->sharedTool();
      probe->touching = false;  // the mouse decides (left button)
      capture_factor = haptic->capture() / probe->radius;
    } else {
      probe = std::make_shared<haptics::ToolState>();
      attachProbe(*scene, probe);
    }
    instruments = haptics::InstrumentSet::fromScene(document, options.scene, *scene, 1.0);
    if (instruments) instruments->start();  // devices on their own thread (a Phantom) start sampling
    // Catheters and guidewires ("navigation"): their hubs to the arrow keys, one at a time (a
    // block that only scores an aneurysm's coils has no instrument).
    if (const auto navigation = haptics::NavigationMetrics::fromScene(document, options.scene, *scene);
        navigation && !hub_device)
      for (int i = 0; i < navigation->instrumentCount(); ++i)
        if (auto hub = haptics::HubControl::find(*scene, navigation->instrument(i).name)) hubs.push_back(std::move(hub));
    pedal = haptics::FluoroscopyPedal::fromScene(document, options.scene);
    fluoroscopy = visual::FluoroscopyView::fromScene(document, options.scene);
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  }
  const SceneState initial = scene->state();

  try {
    std::vector<std::unique_ptr<visual::WoundVisual>> wound_models;  // a wound's lips, drawn as slabs
    visual::VisualScene visuals(*scene);                             // (it keeps pointers to them)
    if (instruments && instruments->wound())
      for (int lip = 0; lip < 2; ++lip) {
        wound_models.push_back(std::make_unique<visual::WoundVisual>(*instruments->wound(), lip));
        visuals.drawBodyWith(instruments->wound()->lip(lip), *wound_models.back(), "wound_lip_" + std::to_string(lip));
      }
    visuals.update(scene->state());
    visual::CameraSettings camera;
    if (auto c = visual::readCamera(document, options.scene)) {
      camera = *c;
    } else {
      Vec3 lower(-0.05, -0.05, -0.05), upper(0.05, 0.05, 0.05);
      visuals.bounds(lower, upper);
      camera = visual::frameBox(lower, upper);
    }
    if (!haptic || options.probe_radius)
      probe->radius = options.probe_radius.value_or(0.02 * (camera.look_at - camera.position).norm());
    visual::ProbeVisual probe_visual(probe);
    std::vector<visual::VisualModel*> models = visuals.models();
    models.push_back(&probe_visual);
    // The instruments and needles, drawn as in `filum run --render`.
    std::vector<std::unique_ptr<visual::VisualModel>> instrument_models;
    if (instruments) {
      for (int i = 0; i < instruments->size(); ++i)
        for (auto part : {visual::InstrumentVisual::Part::kShaft, visual::InstrumentVisual::Part::kJaws})
          instrument_models.push_back(std::make_unique<visual::InstrumentVisual>(instruments->instrument(i), part));
      for (int k = 0; k < instruments->needleCount(); ++k)
        instrument_models.push_back(std::make_unique<visual::NeedleVisual>(instruments->needle(k)));
      for (auto& m : instrument_models) models.push_back(m.get());
    }
    int selected = -1;          // the instrument the mouse drives (keys 1-9; 0: back to the probe)
    double hinge_depth = 0.0;

    visual::OffscreenRenderer renderer(camera);
    std::unique_ptr<visual::OffscreenRenderer> xray;  // the C-arm's view, its own window and camera
    visual::Image monitor;                            // the last X-ray image (held while the pedal is up)
    bool show_xray = false, hub_moved = false;
    int xray_frames = 0;
    if (fluoroscopy) {
      Vec3 lower(-0.05, -0.05, -0.05), upper(0.05, 0.05, 0.05);
      visuals.bounds(lower, upper);
      visual::FluoroscopyView shown = *fluoroscopy;
      shown.size = std::min(camera.width, camera.height);
      xray = std::make_unique<visual::OffscreenRenderer>(shown.camera(fluoroscopy->isocenter.value_or(0.5 * (lower + upper))));
      fluoroscopy = shown;
      monitor = visual::Image(shown.size, shown.size);
      pedal->release(0.0);  // the hand's pedal: up until f
    }
    visual::ViewerWindow window(camera.width, camera.height, "filum view: " + scene->settings().name);
    log << "filum view: " << scene->settings().name
        << " — left drag: push, Shift+left or g: grab, right drag: orbit, wheel: zoom, space: pause, r: restart, "
           "q: quit\n";

    const double dt = scene->settings().dt;
    bool paused = false, grab_mode = false, quit = false, left_down = false, right_down = false;
    double probe_depth = 0.0;
    int last_x = 0, last_y = 0;
    auto last = Clock::now();
    double wall_per_ms = -1.0;
    visual::Image frame;
    for (int index = 0; !quit && (options.frames <= 0 || index < options.frames); ++index) {
      // Events: the probe follows the pointer in the plane facing the camera.
      visual::WindowEvent e;
      while (window.poll(e)) {
        using Type = visual::WindowEvent::Type;
        if (e.type == Type::kClose) quit = true;
        if (e.type == Type::kKey) {
          if (e.key == "q" || e.key == "Escape") quit = true;
          if (e.key == "space") paused = !paused;
          if (e.key == "g") grab_mode = !grab_mode;
          // A hub: a stroke of 5 mm or 15° over 0.1 s a press; Tab passes the arrows to the next
          // instrument's hub (the wire's, then the catheter's over it, ...).
          if (hubs.size() > 1 && e.key == "Tab") hub_index = (hub_index + 1) % hubs.size();
          if (!hubs.empty()) {
            haptics::HubControl& hub = *hubs[hub_index];
            try {
              if (e.key == "Up" || e.key == "Down") {
                hub.push(*scene, e.key == "Up" ? 5e-3 : -5e-3, 0.1);
                hub_moved = true;
              }
              if (e.key == "Left" || e.key == "Right")
                hub_moved |= hub.turn(*scene, (e.key == "Left" ? 15.0 : -15.0) * std::numbers::pi / 180.0, 0.1);
            } catch (const SceneError& error) {  // the hub's constraint let go (released, cut): no more keys
              dropHub(hubs, hub_index, hub_index, error, log);
            }
          }
          if (fluoroscopy && e.key == "x") show_xray = !show_xray;
          if (fluoroscopy && e.key == "f") {
            const double t = scene->state().time;
            if (pedal->on(t))
              pedal->release(t);
            else
              pedal->press(t);
          }
          if (instruments && e.key.size() == 1 && e.key[0] >= '0' && e.key[0] <= '9') {
            const int k = e.key[0] - '1';
            selected = -1;
            if (k >= 0 && k < instruments->size() && instruments->takeOver(k, scene->state().time)) selected = k;
          }
          if (selected >= 0 && (e.key == "c" || e.key == "o"))
            instruments->moveJaws(selected, e.key == "c", scene->state().time);
          // [ and ]: the needle the mouse's instrument holds turned about its own centre, 10° over
          // 0.2 s a press (] drives it towards its tip: through the tissue along its curve).
          if (selected >= 0 && (e.key == "bracketleft" || e.key == "bracketright") &&
              !instruments->turnNeedle(selected, (e.key == "bracketright" ? 10.0 : -10.0) * std::numbers::pi / 180.0,
                                       scene->state().time))
            log << "filum view: [ and ] turn a needle the mouse's instrument holds; '"
                << instruments->instrument(selected).name() << "' holds none (or works through a trocar)\n";
          if (e.key == "r" && (instruments || hub_moved || hub_device)) {
            // The instruments' holds, cuts and metrics are not rewound with the state.
            // The hand's strokes, the instruments' holds, cuts and metrics are not rewound with the state.
            log << "filum view: r does not restart a scene whose instruments or hub the hand has moved; quit and open it "
                   "again\n";
          } else if (e.key == "r") {
            scene->setState(initial);
            probe->touching = false;
            haptics::release(*probe);
          }
        }
        if (e.type == Type::kButtonPress && e.button == 1 && selected >= 0) {
          // The selected instrument's hinge to the pointer, at the hinge's depth.
          left_down = true;
          const double t = scene->state().time;
          hinge_depth = visual::project(camera, instruments->instrument(selected).poseAt(t).hinge).depth;
          instruments->steer(selected, visual::unproject(camera, e.x, e.y, hinge_depth), t);
        } else if (e.type == Type::kButtonPress && e.button == 1) {
          left_down = true;
          probe_depth = pickDepth(*scene, camera, e.x, e.y);
          probe->position = visual::unproject(camera, e.x, e.y, probe_depth);
          probe->touching = true;
          if (grab_mode || e.shift) haptics::startGrasp(*probe, *scene, capture_factor * probe->radius);
        }
        if (e.type == Type::kButtonRelease && e.button == 1) {
          left_down = false;
          probe->touching = false;
          haptics::release(*probe);
        }
        if (e.type == Type::kButtonPress && e.button == 3) right_down = true;
        if (e.type == Type::kButtonRelease && e.button == 3) right_down = false;
        if (e.type == Type::kButtonPress && (e.button == 4 || e.button == 5)) {
          const double factor = e.button == 4 ? 0.9 : 1.0 / 0.9;
          camera.position = camera.look_at + factor * (camera.position - camera.look_at);
          renderer.setCamera(camera);
        }
        if (e.type == Type::kMotion) {
          if (left_down && selected >= 0)
            instruments->steer(selected, visual::unproject(camera, e.x, e.y, hinge_depth), scene->state().time);
          else if (left_down)
            probe->position = visual::unproject(camera, e.x, e.y, probe_depth);
          if (right_down) {
            orbit(camera, -0.01 * (e.x - last_x), -0.01 * (e.y - last_y));
            renderer.setCamera(camera);
          }
          last_x = e.x;
          last_y = e.y;
        }
      }
      // Advance the simulation by the elapsed wall time (or a fixed step), at most 0.1 s per frame.
      const auto now = Clock::now();
      const double elapsed = std::chrono::duration<double>(now - last).count();
      last = now;
      if (!paused) {
        const double advance = std::min(0.1, options.fixed_step.value_or(elapsed * options.speed));
        const long steps = std::max(1L, std::lround(advance / dt));
        const auto before = Clock::now();
        for (long k = 0; k < steps; ++k) {
          for (std::size_t h = 0; h < hubs.size();) {
            try {
              hubs[h]->update(*scene);
              ++h;
            } catch (const SceneError& error) {
              dropHub(hubs, h, hub_index, error, log);
            }
          }
          if (instruments) instruments->beforeStep(*scene);
          if (hub_device) hub_device->beforeStep(*scene);
          const StepReport report = scene->step();
          if (instruments && report.ok) instruments->afterStep(*scene);
          if (hub_device && report.ok) hub_device->afterStep(*scene);
          if (hub_device && !hub_device->lost().empty() && !hub_lost_logged) {
            log << "filum view: " << hub_device->lost() << '\n';
            hub_lost_logged = true;
          }
          if (!report.ok) {
            log << "error: " << report.message << " (state rolled back; press r to restart)\n";
            paused = true;
            break;
          }
        }
        wall_per_ms = std::chrono::duration<double>(Clock::now() - before).count() / (steps * dt);
      }
      // Draw.
      visuals.update(scene->state());
      probe_visual.update(scene->state());
      for (auto& m : instrument_models) m->update(scene->state());
      std::string hud = visual::headsUpText(scene->state().time, wall_per_ms, scene->energy(scene->state()).total());
      if (fluoroscopy) {
        const double t = scene->state().time;
        if (pedal->on(t)) monitor = fluoroscopy->finish(xray->render(models, visual::OffscreenRenderer::Style::kXray), xray_frames++);
        std::ostringstream fluoro;
        fluoro.precision(3);
        fluoro << " | fluoro " << pedal->time(t) << " s" << (pedal->on(t) ? " (X-ray on)" : "");
        hud += fluoro.str();
      }
      if (show_xray) {
        // The monitor, centred on the window's background.
        frame = visual::Image(camera.width, camera.height);
        const int x0 = (camera.width - monitor.width) / 2, y0 = (camera.height - monitor.height) / 2;
        for (int y = 0; y < monitor.height; ++y)
          std::copy_n(monitor.bgr.begin() + 3 * static_cast<std::size_t>(y) * monitor.width, 3 * monitor.width,
                      frame.bgr.begin() + 3 * (static_cast<std::size_t>(y + y0) * frame.width + x0));
      } else {
        frame = renderer.render(models);
      }
      if (paused) hud += " | paused";
      if (grab_mode) hud += " | grab mode";
      if (selected >= 0)
        hud += " | mouse: " + instruments->instrument(selected).name() +
               (instruments->instrument(selected).jawsClosing() ? " (jaws closing)" : "");
      if (!hubs.empty()) {  // the hub the arrows drive
        const haptics::HubControl& hub = *hubs[hub_index];
        std::ostringstream keyed;
        keyed.precision(3);
        keyed << " | arrows: " << hub.name() << " " << 1e3 * hub.insertion(*scene) << " mm, "
              << hub.roll(*scene) * 180.0 / std::numbers::pi << " deg";
        hud += keyed.str();
      }
      if (hub_device) {  // what the hand on the hub feels
        std::ostringstream felt;
        felt.precision(3);
        felt << " | hub " << 1e3 * hub_device->hub().insertion(*scene) << " mm, "
             << hub_device->hub().roll(*scene) * 180.0 / std::numbers::pi << " deg"
             << (hub_device->gripping() ? ", gripped" : "") << " | hand force " << hub_device->handForce().norm()
             << " N, torque " << hub_device->handTorque() << " N m";
        hud += felt.str();
      }
      if (haptic) {  // what a device's hand would feel: the tool's reaction
        std::ostringstream force;
        force.precision(3);
        force << " | hand force " << haptic->reaction(*scene).force.norm() << " N";
        hud += force.str();
      }
      visual::drawHeadsUp(frame, hud);
      visual::drawFooter(frame, instruments ? "1-9: instrument to the mouse, 0: probe | c/o: close/open jaws | [/]: turn needle | "
                                              "left: move | right: orbit | wheel: zoom | space | r | q"
                                : !hubs.empty() || hub_device
                                            ? std::string(!hubs.empty() ? "up/down: push/pull the hub | left/right: turn it"
                                                                        : "the hub on the haptic device (grip: its button)") +
                                                  (hubs.size() > 1 ? " | tab: next instrument" : "") +
                                                  (fluoroscopy ? " | f: X-ray pedal | x: monitor/3D" : "") + " | space | q"
                                            : "left: push | shift+left or g: grab | right: orbit | wheel: zoom | space: pause | r | q");
      window.show(frame);
      if (options.on_frame) options.on_frame(ViewFrame{index, window, *scene, camera, *probe, instruments.get(), selected, hud});
    }
    if (!options.screenshot.empty() && !frame.empty()) visual::writePng(options.screenshot, frame);
  } catch (const SceneError& e) {
    log << "error: " << e.what() << '\n';
    return kRunSceneError;
  } catch (const std::exception& e) {
    log << "error: filum view: " << e.what() << '\n';
    return kRunIoError;
  }
  return kRunOk;
}

}  // namespace filum::app
