#include "filum/haptics/haptic_session.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include <Eigen/SVD>

#include "filum/core/node.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/haptics/device_factory.hpp"
#include "filum/haptics/interrupt.hpp"

namespace filum::haptics {

namespace {

/// The servo log holds the run's ticks and 10 % more (a threaded servo runs on while the
/// simulation catches up), one second at least, and kMaxLogSamples at most.
std::size_t logCapacity(double duration, double rate) {
  const double ticks = std::ceil((1.1 * duration + 1.0) * rate);
  return ticks >= static_cast<double>(kMaxLogSamples) ? kMaxLogSamples : static_cast<std::size_t>(ticks);
}

/// The device's limits: the preset its "model" names, with the block's "limits" over it.
DeviceLimits readLimits(const Params& p, const Params& device) {
  DeviceLimits limits;
  const std::string model = device.string("model", "Touch");
  try {
    limits = devicePreset(model);
  } catch (const std::invalid_argument&) {
    device.fail("model", "a device model among " + devicePresetNames(), "\"" + model + "\"");
  }
  if (p.has("limits")) {
    const Params l = p.object("limits");
    limits = limitsFromParams(l, limits);
    l.finish();
  }
  return limits;
}

/// "rate", "frame", "watchdog" and "fade".
ServoSettings readServoSettings(const Params& p) {
  ServoSettings settings;
  settings.rate = p.positive({"rate", "Hz"}, 1000.0);
  if (settings.rate < kMinServoRate || settings.rate > kMaxServoRate)
    p.fail("rate", "a servo rate in [100, 10000] Hz (below 100 Hz a stiff coupling buzzes; 1 kHz is a Phantom's)");
  if (p.has("frame")) {
    const Params f = p.object("frame");
    settings.frame = deviceFrameFromParams(f);
    f.finish();
  }
  settings.safety.watchdog = p.positive({"watchdog", "s"}, settings.safety.watchdog);
  settings.safety.fade = p.positive({"fade", "s"}, settings.safety.fade);
  return settings;
}

}  // namespace

std::unique_ptr<HapticSession> HapticSession::fromScene(const nlohmann::json& document, const std::string& source,
                                                        Scene& scene, double duration) {
  if (!document.is_object() || !document.contains("haptics")) return nullptr;
  const Params top(document, source, "");
  const Params p = top.object("haptics").withOwner("haptics");
  std::unique_ptr<HapticSession> session(new HapticSession());
  HapticSession& s = *session;
  s.configure(p);
  const Params tool = p.object("tool");
  s.readTool(tool, scene);
  tool.finish();
  p.finish();
  s.servo_ = std::make_unique<ServoLoop>(*s.device_, s.settings_, logCapacity(duration, s.settings_.rate));
  s.attachTool(scene);
  return session;
}

std::unique_ptr<HapticSession> HapticSession::forInstrument(const Params& p, std::shared_ptr<ToolState> hold,
                                                            double duration) {
  std::unique_ptr<HapticSession> session(new HapticSession());
  HapticSession& s = *session;
  s.configure(p);
  s.drives_instrument_ = true;
  s.tool_ = std::move(hold);
  // The coupling the hand feels through is the instrument's hold on the thread.
  s.tool_->grasp_stiffness = s.coupling_.stiffness;
  s.tool_->grasp_damping = s.coupling_.damping;
  s.servo_ = std::make_unique<ServoLoop>(*s.device_, s.settings_, logCapacity(duration, s.settings_.rate));
  return session;
}

void HapticSession::configure(const Params& p) {
  HapticSession& s = *this;
  const Params device = p.object("device");
  const DeviceLimits limits = readLimits(p, device);
  s.settings_ = readServoSettings(p);
  if (p.has("coupling")) {
    const Params c = p.object("coupling");
    s.coupling_ = couplingFromParams(c, limits, s.settings_.frame, 1.0 / s.settings_.rate);
    c.finish();
  } else {
    s.coupling_ = defaultCoupling(limits, s.settings_.frame, 1.0 / s.settings_.rate);
  }
  s.device_ = makeDevice(device, limits);
  device.finish();
  const std::string mode = p.string("mode", s.device_->canRunLockstep() ? "lockstep" : "thread");
  if (mode != "lockstep" && mode != "thread") p.fail("mode", "\"lockstep\" or \"thread\"");
  if (mode == "lockstep" && !s.device_->canRunLockstep())
    p.fail("mode", "\"thread\" for " + s.device_->name() + " (a physical device runs on the wall clock)", "\"lockstep\"");
  s.threaded_ = mode == "thread";
}

bool HapticSession::stylus(const Scene& scene, ServoSample& sample) {
  if (!threaded_) servo_->runLockstepUntil(scene.state().time);
  if (!servo_->latestSample(sample)) return false;
  // On the wall clock the sample is taken as the stylus now, at the step's start.
  if (threaded_) sample.time = scene.state().time;
  return true;
}

void HapticSession::publish(LocalLinearModel model) {
  limitStiffness(model);
  servo_->publish(model);
}

void HapticSession::publishInstrument(const Scene& scene, const Vec3& contact_force, const Vec3& position,
                                      const Vec3& velocity, bool mirrored) {
  const ToolReaction reaction = this->reaction(scene);
  LocalLinearModel model;
  // Through a trocar the hand holds the lever's other end: F_hand = −F_tip, while x_tip = 2p − x_hand
  // leaves ∂F_hand/∂x_hand = ∂F_tip/∂x_tip (two sign changes).
  model.force = (mirrored ? -1.0 : 1.0) * (reaction.force + contact_force);
  model.stiffness = reaction.stiffness;
  model.damping = reaction.damping;
  model.position = position;
  model.velocity = velocity;
  model.time = scene.state().time;
  limitStiffness(model);
  servo_->publish(model);
}

void HapticSession::readTool(const Params& tool, const Scene& scene) {
  const std::string type = tool.string("type");
  tool_->grasp_stiffness = coupling_.stiffness;
  tool_->grasp_damping = coupling_.damping;
  if (type == "Grasper") {
    tool_->radius = tool.positive({"radius", "m"}, 1e-3);
    capture_ = tool.positive({"capture", "m"}, 3.0 * tool_->radius);
    button_mask_ = 1u << (tool.integer("button", 1, 16, 1, "a button of the stylus, 1 to 16") - 1);
    tool_->touching = tool.boolean("push", true);
    tool_->push_stiffness = tool.positive({"push_stiffness", "N/m"}, coupling_.stiffness);
  } else if (type == "Attachment") {
    grasper_ = false;
    attach_object_ = tool.string("object");
    attach_abscissa_ = tool.abscissa("abscissa");
    const MechanicalState* body = scene.bodyAt(attach_object_);
    if (!body || !body->curve()) tool.fail("object", "the path of a node holding a curve body (e.g. \"thread\")");
  } else {
    tool.fail("type", "\"Grasper\" or \"Attachment\"", "\"" + type + "\"");
  }
}

HapticSession::~HapticSession() { finish(); }

void HapticSession::attachTool(Scene& scene) {
  std::vector<ToolForceField*> added;
  for (MechanicalState* body : scene.bodies()) {
    if (!body->curve()) continue;
    auto field = std::make_unique<ToolForceField>(tool_);
    field->setName("haptic tool");
    field->setOrigin(scene.settings().source + ": /haptics/tool (on " + body->describe() + ")");
    added.push_back(field.get());
    body->node()->addComponent(std::move(field));
  }
  scene.init();
  fields_.assign(added.begin(), added.end());
  if (!grasper_) grasp(*tool_, *scene.bodyAt(attach_object_)->curve(), attach_abscissa_);  // a curve body: readTool
}

void HapticSession::start() {
  installInterruptHandler();
  if (threaded_ && !started_) servo_->startThread();
  started_ = true;
}

void HapticSession::beforeStep(const Scene& scene) {
  if (!threaded_) servo_->runLockstepUntil(scene.state().time);
  ServoSample sample;
  if (!servo_->latestSample(sample)) return;  // no tick since the last step: the tool stays
  tool_->position = sample.position;
  tool_->velocity = sample.velocity;
  // The sample's time on the simulation's clock: in lockstep the servo time is the simulated
  // time; on the wall clock the sample is taken as the stylus now, at the step's start.
  tool_->time = threaded_ ? scene.state().time : sample.time;
  if (!grasper_) return;
  const bool pressed = (sample.buttons & button_mask_) != 0;
  if (pressed && !was_pressed_) grasps_ += startGrasp(*tool_, scene, capture_);
  if (!pressed && was_pressed_) release(*tool_);
  was_pressed_ = pressed;
}

ToolReaction HapticSession::reaction(const Scene& scene) const {
  ToolReaction reaction;
  for (const ToolForceField* field : fields_) field->addReaction(scene.state(), reaction);
  return reaction;
}

void HapticSession::afterStep(const Scene& scene) {
  const ToolReaction reaction = this->reaction(scene);
  LocalLinearModel model;
  model.force = reaction.force;
  model.stiffness = reaction.stiffness;
  model.damping = reaction.damping;
  // Around the stylus as the step assumed it at its end (toolPosition), so that the servo's
  // K (x − x0) adds only what the hand did beyond that prediction.
  model.position = toolPosition(*tool_, scene.state().time);
  model.velocity = tool_->velocity;
  model.time = scene.state().time;
  limitStiffness(model);
  servo_->publish(model);
}

void HapticSession::limitStiffness(LocalLinearModel& model) const {
  // Felt on the device: K_d = force_scale · scale · Rᵀ K R, same for D; its largest singular
  // value against the bound b > K T/2 + |B| (with the felt damping) and max_stiffness.
  const DeviceLimits& limits = device_->limits();
  const double period = servo_->period();
  const Eigen::JacobiSVD<Eigen::Matrix3d> K(settings_.frame.gainToDevice(model.stiffness));
  const Eigen::JacobiSVD<Eigen::Matrix3d> D(settings_.frame.gainToDevice(model.damping));
  const double k = K.singularValues()(0), b = D.singularValues()(0);
  const double bound = std::min(limits.max_stiffness, std::max(0.0, 2.0 * (limits.damping - b) / period));
  if (k > bound) model.stiffness *= bound / k;
}

void HapticSession::finish() {
  if (servo_) servo_->stop();
}

bool HapticSession::interrupted() const { return servo_->interrupted() || interruptRequested(); }

void HapticSession::writeCsv(const std::string& path) const {
  std::ofstream out(path);
  out << "time,period,x,y,z,buttons,commanded_x,commanded_y,commanded_z,sent_x,sent_y,sent_z,watchdog_gain,roll,"
         "torque_commanded,torque_sent\n";
  out.precision(17);
  for (const ServoSample& s : servo_->log()) {
    out << s.time << ',' << s.period << ',' << s.position.x() << ',' << s.position.y() << ',' << s.position.z() << ','
        << s.buttons << ',';
    // A non-finite command (refused by ForceSafety, sent as zero) is written as "nan" so that
    // the plot shows the refusal; sent forces are finite by construction.
    for (int i = 0; i < 3; ++i) out << s.commanded[i] << ',';
    for (int i = 0; i < 3; ++i) out << s.sent[i] << ',';
    out << s.watchdog_gain << ',' << s.roll << ',' << s.torque_commanded << ',' << s.torque_sent << '\n';
  }
  out.close();
  if (!out) throw std::runtime_error(path + ": write failed (disk full or file size limit?)");
}

std::string HapticSession::summary() const {
  const auto& log = servo_->log();
  double peak = 0.0, longest = 0.0, peak_torque = 0.0;
  for (const ServoSample& s : log) {
    peak = std::max(peak, s.sent.norm());
    peak_torque = std::max(peak_torque, std::abs(s.torque_sent));
    longest = std::max(longest, s.period);
  }
  std::ostringstream out;
  out << "haptics: " << device_->name() << ", " << servo_->ticks() << " servo ticks at " << settings_.rate << " Hz ("
      << (threaded_ ? "thread" : "lockstep") << "), ";
  if (coupling_used_) out << "coupling k = " << coupling_.stiffness << " N/m, c = " << coupling_.damping << " N·s/m, ";
  out << "largest force sent " << peak << " N, longest period "
      << longest * 1e3 << " ms";
  if (peak_torque > 0.0) out << ", largest torque sent " << peak_torque << " N·m";
  if (!drives_instrument_) out << ", " << grasps_ << " grasps";  // an instrument's are in its metrics
  if (servo_->safety().nonFiniteCount() > 0) out << ", " << servo_->safety().nonFiniteCount() << " non-finite forces refused";
  if (servo_->safety().nonFiniteTorqueCount() > 0)
    out << ", " << servo_->safety().nonFiniteTorqueCount() << " non-finite torques refused";
  if (servo_->droppedSamples() > 0) out << ", " << servo_->droppedSamples() << " samples beyond the log dropped";
  if (const std::string note = device_->schedulingNote(); !note.empty()) out << "\n  note: " << note;
  return out.str();
}

}  // namespace filum::haptics
