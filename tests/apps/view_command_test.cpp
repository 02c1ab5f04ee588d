// `filum view` under Xvfb: the window opens, plays the scene, and mouse events sent to
// it through the X server (a Shift + left press on the thread, drags, release) make the probe
// grab the thread and pull it; q closes it. Skipped only if there is no DISPLAY and Xvfb is not
// installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <vector>

#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/core/node.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/rod_end_frame.hpp"
#include "filum/visual/image_file.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/run_command.hpp"
#include "filum/view_command.hpp"
#include "visual/visual_test_support.hpp"

namespace filum::app {
namespace {

namespace fs = std::filesystem;
using visual::WindowEvent;

/// apps/scenes/<scene_file> played for `frames` frames of `fixed_step` of simulation each (20 ms by
/// default), whatever the machine's speed.
ViewOptions playing(const std::string& scene_file, int frames, double fixed_step = 0.02) {
  ViewOptions view;
  view.scene = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/" + scene_file;
  view.frames = frames;
  view.fixed_step = fixed_step;
  return view;
}

/// Shift + left press on the middle of the scene's first thread, a drag of 120 pixels right and
/// 60 up, then 0.26 s held still: the grabbed point must be at the probe.
void expectMouseGrabsAndPulls(const std::string& scene_file, const std::string& screenshot) {
  FILUM_REQUIRE_RENDERING();

  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "view";
  fs::create_directories(out);
  ViewOptions options = playing(scene_file, 24);
  options.screenshot = (out / screenshot).string();
  bool grabbed = false, mapped = false;
  double grab_abscissa = 0.0;
  Vec3 target = Vec3::Zero(), reached = Vec3::Zero();
  int target_u = 0, target_v = 0;
  options.on_frame = [&](const ViewFrame& f) {
    const auto& spline = *f.scene.bodies().front()->curve();
    const ConstPointsMap q = spline.block(f.scene.state().q);
    if (f.index == 0) mapped = f.window.mapped();
    if (f.index == 3) {
      // Shift + left press on the thread's middle.
      const visual::Pixel p = visual::project(f.camera, geometry::curvePoint(spline.basis(), q, 0.5));
      f.window.sendToSelf({WindowEvent::Type::kButtonPress, static_cast<int>(p.u), static_cast<int>(p.v), 1, true, ""});
      target_u = static_cast<int>(p.u) + 120;  // drag 120 pixels to the right, 60 up
      target_v = static_cast<int>(p.v) - 60;
    }
    if (f.index == 4) {
      grabbed = f.probe.grasping;
      grab_abscissa = f.probe.grasp.abscissa();
    }
    if (f.index > 4 && f.index <= 10)  // drag in 6 moves
      f.window.sendToSelf({WindowEvent::Type::kMotion, target_u - 20 * (10 - f.index), target_v + 10 * (10 - f.index), 0, true, ""});
    if (f.index == 23) {
      target = f.probe.position;
      reached = geometry::curvePoint(spline.basis(), q, grab_abscissa);
      f.window.sendToSelf({WindowEvent::Type::kButtonRelease, target_u, target_v, 1, true, ""});
    }
  };
  std::ostringstream log;
  ASSERT_EQ(viewScene(options, log), kRunOk) << log.str();
  EXPECT_TRUE(mapped) << scene_file;
  EXPECT_TRUE(grabbed) << scene_file << ": the Shift + left press on the thread did not grab it";
  EXPECT_NEAR(grab_abscissa, 0.5, 0.05) << scene_file;
  // After 0.26 s of holding the probe still, the grabbed point is at the probe (within 2 mm).
  EXPECT_LT((reached - target).norm(), 2e-3) << scene_file << ": probe " << target.transpose() << ", point "
                                              << reached.transpose();
  EXPECT_EQ(visual::readPng(options.screenshot).width, 960);
}

TEST(ViewCommand, MouseGrabsAndPullsTheThread) {
  // The soft-spring thread, whose middle can follow a probe dragged 3 cm away. (Without a
  // "haptics" block the mouse sets no stiffness: the tool takes the explicit step's cap, ω dt =
  // 0.5, haptics/src/tool.cpp — ~0.03 N/m on the headline suture's 1e-7 kg, too soft for it.)
  expectMouseGrabsAndPulls("paper_hanging_thread.json", "view_last_frame.png");
}

TEST(ViewCommand, TheMouseTakesTheHapticToolOfTheScene) {
  // A real suture (implicit, 1 ms) with a "haptics" block: the mouse drives the block's tool,
  // with its coupling (900 N/m), stiff enough to carry the 2 GPa thread's middle along.
  expectMouseGrabsAndPulls("haptic_grasp.json", "view_haptic_last_frame.png");
}

/// An instrument's hub as the keys move it: its point constraint at s = 0 and its RodEndFrame.
struct Hub {
  const constraints::ProjectedPointConstraint* point = nullptr;
  const mechanics::RodEndFrame* frame = nullptr;
};

Hub hubOf(const Scene& scene, const std::string& instrument) {
  Hub hub;
  const Node* node = const_cast<Scene&>(scene).root().find(instrument);
  if (!node) return hub;
  for (const auto& c : node->components()) {
    if (const auto* p = dynamic_cast<const constraints::ProjectedPointConstraint*>(c.get()); p && p->abscissa() == 0.0)
      hub.point = p;
    if (const auto* r = dynamic_cast<const mechanics::RodEndFrame*>(c.get())) hub.frame = r;
  }
  return hub;
}

TEST(ViewCommand, ArrowsPushAndTurnACathetersHubAndTheMonitorShowsTheXRay) {
  // apps/scenes/guidewire.json: Up pushes the guidewire's hub 5 mm along the introducer's axis
  // (over 0.1 s, then held; its scripted path dropped; a second press during a stroke adds its
  // own), Left turns it 15° (RodEndFrame::turn);
  // f presses the fluoroscopy pedal and x puts the fluoroscope's monitor in the window: a grey
  // picture.
  FILUM_REQUIRE_RENDERING();
  const fs::path out = fs::path(FILUM_BINARY_DIR) / "test_output" / "view";
  fs::create_directories(out);
  ViewOptions options = playing("guidewire.json", 30);
  options.screenshot = (out / "catheter_monitor.png").string();
  // The wire starts straight up the introducer's axis, +z: the hub's initial tangent, exactly.
  const Vec3 axis = Vec3::UnitZ();
  Vec3 before = Vec3::Zero(), after = Vec3::Zero(), hub_point = Vec3::Zero();
  double roll_before = -1.0, roll_after = -1.0;
  options.on_frame = [&](const ViewFrame& f) {
    Node& wire = *const_cast<Scene&>(f.scene).root().find("guidewire");
    const auto [hub, frame] = hubOf(f.scene, "guidewire");
    ASSERT_NE(hub, nullptr);
    ASSERT_NE(frame, nullptr);
    const double t = f.scene.state().time;
    if (f.index == 2) {
      before = hub->target().position(f.scene.state());
      f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "Up"});  // two strokes at once: 10 mm
      f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "Up"});
    }
    if (f.index == 5) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "f"});
    if (f.index == 6) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "x"});
    if (f.index == 20) {
      after = hub->target().position(f.scene.state());
      hub_point = wire.mechanicalState()->curve()->position(f.scene.state().q, 0.0);
      roll_before = frame->roll(t);
      f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "Left"});
    }
    if (f.index == 29) roll_after = frame->roll(t);
  };
  std::ostringstream log;
  ASSERT_EQ(viewScene(options, log), kRunOk) << log.str();
  // The target moved by exactly the two strokes along the axis (round-off of the 0.3 m coordinates).
  EXPECT_LT((after - before - 10e-3 * axis).norm(), 1e-12) << (after - before).transpose();
  // The hub follows its target through the constraint (Baumgarte-stabilized: well within 0.1 mm
  // once the stroke is 0.24 s old).
  EXPECT_LT((hub_point - after).norm(), 1e-4);
  EXPECT_NEAR(roll_after - roll_before, 15.0 * M_PI / 180.0, 1e-12);
  // The monitor: a grey picture (every pixel b = g = r) in its middle.
  const visual::Image shot = visual::readPng(options.screenshot);
  int coloured = 0;
  for (int y = shot.height / 4; y < 3 * shot.height / 4; ++y)
    for (int x = shot.width / 4; x < 3 * shot.width / 4; ++x) {
      const auto [b, g, r] = shot.at(x, y);
      coloured += !(b == g && g == r);
    }
  EXPECT_EQ(coloured, 0);
}

TEST(ViewCommand, TabPassesTheArrowsFromTheWiresHubToTheCatheters) {
  // apps/scenes/catheter.json (a guidewire and a catheter over it, their hubs pushed by a script
  // along the introducer's axis, +z, 3.25 cm/s for 6 s): the arrows start on the first
  // instrument of the "navigation" block, the wire; Tab passes them to the catheter. Its Up and
  // Left then move the catheter's hub (5 mm along the axis, 15°) and leave the wire on its script.
  FILUM_REQUIRE_RENDERING();
  ViewOptions options = playing("catheter.json", 12);
  const Vec3 axis = Vec3::UnitZ();
  Vec3 catheter_before = Vec3::Zero(), catheter_after = Vec3::Zero(), wire_before = Vec3::Zero(), wire_after = Vec3::Zero();
  double t_before = 0.0, t_after = 0.0, catheter_roll = 0.0, wire_roll = -1.0;
  std::string hud_before, hud_after;  // the heads-up line names the hub the arrows drive
  options.on_frame = [&](const ViewFrame& f) {
    if (f.index == 2) hud_before = f.heads_up;
    if (f.index == 11) hud_after = f.heads_up;
    const Hub wire = hubOf(f.scene, "guidewire"), catheter = hubOf(f.scene, "catheter");
    ASSERT_TRUE(wire.point && wire.frame && catheter.point && catheter.frame);
    const double t = f.scene.state().time;
    if (f.index == 2) {
      t_before = t;
      wire_before = wire.point->target().position(f.scene.state());
      catheter_before = catheter.point->target().position(f.scene.state());
      catheter_roll = catheter.frame->roll(t);
      for (const char* key : {"Tab", "Up", "Left"}) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, key});
    }
    if (f.index == 11) {  // 0.18 s after the keys: the 0.1-s strokes are over
      t_after = t;
      wire_after = wire.point->target().position(f.scene.state());
      catheter_after = catheter.point->target().position(f.scene.state());
      catheter_roll = catheter.frame->roll(t) - catheter_roll;
      wire_roll = wire.frame->roll(t);
    }
  };
  std::ostringstream log;
  ASSERT_EQ(viewScene(options, log), kRunOk) << log.str();
  ASSERT_GT(t_after, t_before + 0.1);
  // The catheter's hub: exactly the stroke (round-off of the 0.4 m coordinates), and the turn.
  EXPECT_LT((catheter_after - catheter_before - 5e-3 * axis).norm(), 1e-12) << (catheter_after - catheter_before).transpose();
  EXPECT_NEAR(catheter_roll, 15.0 * M_PI / 180.0, 1e-12);
  // The wire's: on its script (0.195 m in 6 s, linear), not turned (its roll starts at 1 s).
  EXPECT_LT((wire_after - wire_before - 0.195 / 6.0 * (t_after - t_before) * axis).norm(), 1e-12)
      << (wire_after - wire_before).transpose();
  EXPECT_EQ(wire_roll, 0.0);
  EXPECT_NE(hud_before.find("arrows: guidewire"), std::string::npos) << hud_before;
  EXPECT_NE(hud_after.find("arrows: catheter"), std::string::npos) << hud_after;
}

TEST(ViewCommand, KeysGiveAnInstrumentToTheMouseAndCloseItsJaws) {
  // apps/scenes/instruments.json: key 2 gives the right grasper to the mouse (its script is left
  // where it was), a left press and a drag carry its hinge to the pointer (at the hinge's depth),
  // c closes its jaws (at 5 per second: shut within 0.2 s, 10 frames of 20 ms).
  FILUM_REQUIRE_RENDERING();
  ViewOptions options = playing("instruments.json", 30);
  int selected = -2;
  double jaw = -1.0;
  Vec3 hinge = Vec3::Zero(), pointer = Vec3::Zero(), start_hinge = Vec3::Zero();
  visual::Pixel start;
  options.on_frame = [&](const ViewFrame& f) {
    ASSERT_NE(f.instruments, nullptr);
    const double t = f.scene.state().time;
    if (f.index == 2) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "2"});
    if (f.index == 4) {
      selected = f.selected;
      start_hinge = f.instruments->instrument(1).poseAt(t).hinge;
      start = visual::project(f.camera, start_hinge);
      f.window.sendToSelf({WindowEvent::Type::kButtonPress, static_cast<int>(start.u), static_cast<int>(start.v), 1, false, ""});
    }
    if (f.index == 6)
      f.window.sendToSelf({WindowEvent::Type::kMotion, static_cast<int>(start.u) - 80, static_cast<int>(start.v) + 40, 0, false, ""});
    if (f.index == 9) {
      hinge = f.instruments->instrument(1).poseAt(t).hinge;
      pointer = visual::unproject(f.camera, static_cast<int>(start.u) - 80, static_cast<int>(start.v) + 40, start.depth);
      f.window.sendToSelf({WindowEvent::Type::kButtonRelease, static_cast<int>(start.u) - 80, static_cast<int>(start.v) + 40, 1, false, ""});
      f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "c"});
    }
    if (f.index == 29) jaw = f.instruments->instrument(1).jawAt(t);
  };
  std::ostringstream log;
  ASSERT_EQ(viewScene(options, log), kRunOk) << log.str();
  EXPECT_EQ(selected, 1);
  // The hinge is the pointer unprojected at its depth (round-off of the camera's 0.3 m).
  EXPECT_LT((hinge - pointer).norm(), 1e-12) << hinge.transpose() << " vs " << pointer.transpose();
  EXPECT_GT((hinge - start_hinge).norm(), 5e-3);  // it moved (80 and 40 pixels at 0.3 m: about 1.5 cm)
  EXPECT_EQ(jaw, 0.0);
}

TEST(ViewCommand, BracketsTurnTheNeedleTheMousesHolderHolds) {
  // apps/scenes/stitch.json: holder A has caught the needle by 0.053 s; key 1 gives A to the mouse,
  // and three presses of ] (10° over 0.2 s each, adding up) turn the needle 30° about its own
  // centre and normal: its centre stays and its swage turns by 30°, to the round-off of composing
  // rigid placements (1e-16 of 0.1 m, a few dozen operations).
  FILUM_REQUIRE_RENDERING();
  ViewOptions options = playing("stitch.json", 30);
  haptics::RigidPose before;
  double centre_moved = -1.0, swage_error = -1.0;
  options.on_frame = [&](const ViewFrame& f) {
    ASSERT_NE(f.instruments, nullptr);
    const haptics::Needle& needle = f.instruments->needle(0);
    if (f.index == 3) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "1"});
    if (f.index == 5) {
      before = needle.pose();
      for (int k = 0; k < 3; ++k) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "bracketright"});
    }
    if (f.index == 29) {  // the needle's pose is measured while the view (and its needle) lives
      const haptics::RigidPose after = needle.pose();
      const Eigen::Matrix3d turn = Eigen::AngleAxisd(M_PI / 6, before.rotation.col(2)).toRotationMatrix();
      centre_moved = (after.position - before.position).norm();
      swage_error = (needle.swage(after) - (before.position + turn * (needle.swage(before) - before.position))).norm();
    }
  };
  std::ostringstream log;
  ASSERT_EQ(viewScene(options, log), kRunOk) << log.str();
  ASSERT_GE(centre_moved, 0.0);
  EXPECT_LT(centre_moved, 64 * 1e-16 * 0.1);
  EXPECT_LT(swage_error, 64 * 1e-16 * 0.1);
}

/// Plays apps/scenes/`scene_file` in the view for at most `frames` frames of `fixed_step`,
/// sending the `keys` at frame `at`; the view must end normally. Returns the frames played.
int framesPlayedWithKeys(const std::string& scene_file, int frames, double fixed_step, int at,
                         const std::vector<std::string>& keys) {
  ViewOptions options = playing(scene_file, frames, fixed_step);
  int played = 0;
  options.on_frame = [&](const ViewFrame& f) {
    played = f.index + 1;
    if (f.index == at)
      for (const std::string& key : keys) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, key});
  };
  std::ostringstream log;
  EXPECT_EQ(viewScene(options, log), kRunOk) << scene_file << ": " << log.str();
  return played;
}

TEST(ViewCommand, ACoilSceneWithoutAHubPlaysAndIgnoresTheArrows) {
  // apps/scenes/coil_in_sac.json: a "navigation" block that scores an aneurysm's coil and has no
  // instrument to push. A smoke test of that case (the view once took instrument 0 of none):
  // with Up, Left and x pressed, it plays its frames and ends normally.
  FILUM_REQUIRE_RENDERING();
  EXPECT_EQ(framesPlayedWithKeys("coil_in_sac.json", 4, 0.002, 1, {"Up", "Left", "x"}), 4);
}

TEST(ViewCommand, AHapticDeviceOnTheHubPushesItAndTheArrowsDoNot) {
  // apps/scenes/catheter_device.json: the hub on a (scripted) stylus. 25 frames of 20 ms: the grip
  // is held from 0 s and the stylus moves 3.9 cm in 1 s, so by 0.5 s the hub is 1.95 cm in (the
  // target from the stylus by arithmetic; the hub within the constraint's error, asked within
  // 0.1 mm while it moves). Up, pressed at frame 2, would push it 5 mm more: not with a device.
  FILUM_REQUIRE_RENDERING();
  ViewOptions options = playing("catheter_device.json", 25);
  double hub_z = 0.0, time = 0.0;
  options.on_frame = [&](const ViewFrame& f) {
    if (f.index == 2) f.window.sendToSelf({WindowEvent::Type::kKey, 0, 0, 0, false, "Up"});
    hub_z = f.scene.bodies().front()->curve()->position(f.scene.state().q, 0.0).z();
    time = f.scene.state().time;
  };
  std::ostringstream log;
  ASSERT_EQ(viewScene(options, log), kRunOk) << log.str();
  ASSERT_NEAR(time, 0.5, 1e-9);
  EXPECT_NEAR(hub_z - (-0.26), 0.0195, 1e-4) << log.str();  // the hub starts at z = −0.26 m
}

TEST(ViewCommand, QuitKeyClosesTheWindow) {
  FILUM_REQUIRE_RENDERING();
  EXPECT_LE(framesPlayedWithKeys("hanging_thread.json", 1000, 0.001, 2, {"q"}), 5);
}

}  // namespace
}  // namespace filum::app
