#include "filum/haptics/hub_device.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "filum/core/params.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::haptics {

std::unique_ptr<HubDevice> HubDevice::fromScene(const nlohmann::json& document, const std::string& source,
                                                Scene& scene, double duration) {
  if (!document.is_object() || !document.contains("navigation") || !document["navigation"].is_object() ||
      !document["navigation"].contains("device"))
    return nullptr;
  const Params top(document, source, "");
  const Params navigation = top.object("navigation").withOwner("navigation");
  const Params p = navigation.object("device").withOwner("navigation device");
  // One device a run, refused before either is opened (both would write haptics.csv).
  if (document.contains("haptics"))
    p.fail("device", "one haptic device a scene: the \"haptics\" block's tool or this one at the hub",
           "both (a \"haptics\" block too)");
  std::unique_ptr<HubDevice> hub(new HubDevice());
  // The instrument: named here, or the navigation block's (first); a refusal names the key it came from.
  const Params* owner = &p;
  std::string key = "instrument", name;
  if (p.has("instrument")) {
    name = p.string("instrument");
  } else if (navigation.has("instrument")) {
    owner = &navigation;
    name = navigation.string("instrument");
  } else if (navigation.has("instruments") && navigation.raw("instruments").is_array() &&
             !navigation.raw("instruments").empty() && navigation.raw("instruments")[0].is_string()) {
    owner = &navigation;
    key = "instruments";
    name = navigation.raw("instruments")[0].get<std::string>();
  } else {
    p.fail("instrument", "the node path of the instrument whose hub the device drives");
  }
  hub->hub_ = HubControl::find(scene, name);
  if (!hub->hub_)
    owner->fail(key, "an instrument (curve body) held at s = 0 by a point constraint (a FixedPointConstraint): its hub",
                "\"" + name + "\"");
  hub->button_mask_ = 1u << (p.integer("button", 1, 16, 1, "a button of the stylus, 1 to 16") - 1);
  hub->roll_scale_ = p.number({"roll_scale", "1"}, 1.0);
  if (!(std::abs(hub->roll_scale_) > 0.0) || !std::isfinite(hub->roll_scale_) || std::abs(hub->roll_scale_) > 100.0)
    p.fail("roll_scale", "a non-zero roll scale of at most 100 in size (hub turns per stylus turn)");
  // The device, its servo loop and safety: a "haptics" block without a tool. Its coupling gains
  // are not used (the hub is driven in position), only checked.
  hub->session_ = HapticSession::forInstrument(p, std::make_shared<ToolState>(), duration);
  hub->session_->setCouplingUsed(false);
  p.finish();
  return hub;
}

void HubDevice::beforeStep(Scene& scene) {
  if (!lost_.empty()) {  // the hub let go: the servo ticks on, the hand feels nothing
    ServoSample ignored;
    session_->stylus(scene, ignored);
    return;
  }
  try {
    drive(scene);
  } catch (const SceneError& e) {  // the hub's constraint released or cut: nothing to push any more
    lost_ = "t = " + std::to_string(scene.state().time) + " s: the hub cannot be driven any more: " + e.what();
    gripping_ = false;
  }
}

void HubDevice::drive(Scene& scene) {
  ServoSample sample;
  if (!session_->stylus(scene, sample)) {
    // No tick since the last step. A stylus gone quiet for longer than the watchdog (a device
    // fault, a stalled servo thread) leaves the hub where it is rather than moving on at the last
    // stroke's speed.
    // The grip ends there: when samples come back, a held button is a new grip from where the
    // stylus then is, not a jump to where the old one would put the hub.
    if (gripping_ && scene.state().time - last_sample_time_ > session_->watchdog()) {
      hub_->steer(scene, hub_->insertion(scene), 0.0);
      gripping_ = false;
    }
    return;
  }
  last_sample_time_ = sample.time;
  const bool pressed = (sample.buttons & button_mask_) != 0;
  if (pressed && !gripping_) {  // the hand closes on the hub
    grip_stylus_ = sample.position;
    grip_roll_ = sample.roll;
    grip_insertion_ = hub_->insertion(scene);
    grip_hub_roll_ = hub_->roll(scene);
    ++strokes_;
  }
  if (!pressed && gripping_) hub_->steer(scene, hub_->insertion(scene), 0.0);  // let go: the hub stays
  gripping_ = pressed;
  if (!gripping_) return;
  const Vec3& axis = hub_->axis();
  // d at the sample's time, moving on at the stylus's speed along a₀; ψ reached at the step's end.
  const double lead = scene.state().time - sample.time;  // the sample's age (0 in lockstep)
  const double speed = sample.velocity.dot(axis);
  hub_->steer(scene, grip_insertion_ + (sample.position - grip_stylus_).dot(axis) + speed * lead, speed);
  hub_->rollTo(scene, grip_hub_roll_ + roll_scale_ * (sample.roll - grip_roll_), scene.settings().dt);
}

void HubDevice::afterStep(const Scene& scene) {
  const Vec3& axis = hub_->axis();
  hand_force_ = gripping_ ? Vec3(-hub_->force(scene).dot(axis) * axis) : Vec3::Zero();
  hand_torque_ = gripping_ ? -roll_scale_ * hub_->torque(scene) : 0.0;
  largest_force_ = std::max(largest_force_, hand_force_.norm());
  largest_torque_ = std::max(largest_torque_, std::abs(hand_torque_));
  LocalLinearModel model;
  model.force = hand_force_;
  model.torque = hand_torque_;
  model.time = scene.state().time;
  session_->publish(model);
}

std::string HubDevice::summary() const {
  std::ostringstream out;
  out << session_->summary() << "\n  hub of " << hub_->name() << ": " << strokes_ << " strokes, largest force on the hand "
      << largest_force_ << " N along the introducer, largest torque " << largest_torque_ << " N·m";
  if (!lost_.empty()) out << "\n  " << lost_;
  return out.str();
}

}  // namespace filum::haptics
