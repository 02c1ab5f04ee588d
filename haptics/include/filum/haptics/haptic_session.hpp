// HapticSession: a scene's "haptics" block at run time — the device, its servo loop, the tool
// it holds, and the exchange with the simulation at every step.
//
//   "haptics": {
//     "device":   {"type": "ScriptedDevice" | "SimulatedDevice" | "OpenHapticsDevice", "model": "Touch", ...},
//     "rate":     1000,                      servo rate (Hz)
//     "mode":     "lockstep" | "thread",     lockstep: the servo ticks run between the steps, on
//                                            the simulation's clock (deterministic; scripted and
//                                            simulated devices only); thread: on the servo thread,
//                                            on the wall clock (a real device; the run is then
//                                            paced to real time). Default: lockstep where possible.
//     "frame":    {"rotation", "scale", "offset", "force_scale"}   (device_frame.hpp)
//     "limits":   {"peak_force", "continuous_force", ..., "damping"}   (device_limits.hpp)
//     "coupling": {"stiffness": N/m, "damping": N·s/m}   checked for passivity (coupling.hpp)
//     "watchdog": 0.05, "fade": 0.05          (s; force_safety.hpp)
//     "tool":     {"type": "Grasper", "radius": m, "capture": m, "button": 1, "push": true,
//                  "push_stiffness": N/m}
//               | {"type": "Attachment", "object": "node/path", "abscissa": s}
//   }
// A Grasper closes on the curve point nearest to the stylus (within "capture") when its button
// is pressed and lets go when it is released; between, its sphere pushes the threads (if "push").
// An Attachment holds the point s of the named body from the start (a thread's end in the hand).
//
// Per step (the run loop): beforeStep — the ticks due run (lockstep) and the newest stylus
// sample moves the tool, the button closes or opens the jaws; the step; afterStep — the tool's
// reaction and its Jacobians at the new state become the servo's local linear model. The model's
// stiffness is limited to what the device renders passively (the tool's push may sum many
// samples), the rest is left to the simulation's rate.
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"
#include "filum/haptics/coupling.hpp"
#include "filum/haptics/haptic_device.hpp"
#include "filum/haptics/servo_loop.hpp"
#include "filum/haptics/tool.hpp"

namespace filum::haptics {

class HapticSession {
 public:
  /// Reads document["haptics"] of the scene file `source` (null when the scene has none), builds
  /// the device and gives the scene's curve bodies the tool's force fields (the scene is bound
  /// again). duration: the run's length (s), for the servo log. Throws SceneError at the faulty
  /// JSON path.
  static std::unique_ptr<HapticSession> fromScene(const nlohmann::json& document, const std::string& source,
                                                  Scene& scene, double duration);
  /// The device, servo loop and coupling of an instrument's "device" block (a "haptics" block
  /// without "tool"): the stylus drives the instrument (InstrumentSet) and `hold`, the
  /// instrument's hold on a thread, takes the coupling's gains. Throws SceneError at p's fields.
  static std::unique_ptr<HapticSession> forInstrument(const Params& p, std::shared_ptr<ToolState> hold,
                                                      double duration);
  ~HapticSession();

  /// For an instrument, before a step: the ticks due (lockstep) and the newest stylus sample
  /// (false: no tick since the last step).
  bool stylus(const Scene& scene, ServoSample& sample);
  /// For an instrument, after a step: the hold's reaction (the fields of setFields) and the
  /// threads' contact force on its parts, around the stylus at `position`, `velocity`.
  /// `mirrored`: the stylus is the hand on the handle of an instrument through a trocar.
  void publishInstrument(const Scene& scene, const Vec3& contact_force, const Vec3& position, const Vec3& velocity,
                         bool mirrored);
  /// For another driver of the device (an instrument's hub, hub_device.hpp), after a step: the
  /// model the servo renders until the next, its stiffness limited as the hand feels it.
  void publish(LocalLinearModel model);
  /// The force fields whose reaction the hand feels (an instrument's holds).
  void setFields(std::vector<const ToolForceField*> fields) { fields_ = std::move(fields); }

  /// Starts the servo loop (thread mode) and the Ctrl-C handler.
  void start();
  void beforeStep(const Scene& scene);
  void afterStep(const Scene& scene);
  /// Stops the servo loop: forces off. Idempotent.
  void finish();
  /// Whether Ctrl-C arrived (the run should stop after its step).
  bool interrupted() const;
  /// Whether the servo runs on its own thread on the wall clock (the run paces itself).
  bool threaded() const { return threaded_; }

  /// haptics.csv: time, period, stylus x y z (scene, m), buttons, commanded and sent force
  /// (device frame, N), watchdog gain, stylus roll (rad), commanded and sent torque about it
  /// (N·m); one row per servo tick (the first kMaxLogSamples).
  void writeCsv(const std::string& path) const;
  /// One line for the run's log: ticks, rate, largest force, clamps, watchdog, dropped samples.
  std::string summary() const;

  /// The tool's reaction on the hand and its Jacobians at the scene's state (what afterStep
  /// publishes, before the stiffness limit).
  ToolReaction reaction(const Scene& scene) const;

  ServoLoop& servo() { return *servo_; }
  const ToolState& tool() const { return *tool_; }
  /// The tool, for another driver than the device (the mouse of `filum view`, which then leaves
  /// the device and its servo loop idle).
  const std::shared_ptr<ToolState>& sharedTool() { return tool_; }
  /// How far from the thread a Grasper's jaws catch it (m).
  double capture() const { return capture_; }
  const CouplingGains& coupling() const { return coupling_; }
  /// Seconds without a new model before the servo fades the force (the block's "watchdog").
  double watchdog() const { return settings_.safety.watchdog; }
  /// Whether the coupling gains act (false for a device that drives an instrument's hub in
  /// position, hub_device.hpp): the summary then leaves them out.
  void setCouplingUsed(bool used) { coupling_used_ = used; }

 private:
  HapticSession() = default;
  /// Device, limits, servo settings, coupling and mode of the block p.
  void configure(const Params& p);
  /// The "tool" block: a Grasper's radius, capture, button, push; an Attachment's body point.
  void readTool(const Params& tool, const Scene& scene);
  void attachTool(Scene& scene);
  /// The model's stiffness, felt on the device, limited to the passive and device bounds.
  void limitStiffness(LocalLinearModel& model) const;

  std::unique_ptr<HapticDevice> device_;
  std::unique_ptr<ServoLoop> servo_;
  std::shared_ptr<ToolState> tool_ = std::make_shared<ToolState>();
  std::vector<const ToolForceField*> fields_;
  ServoSettings settings_;
  CouplingGains coupling_;
  bool threaded_ = false;
  bool coupling_used_ = true;
  bool grasper_ = true;         // else an attachment
  unsigned button_mask_ = 1;
  double capture_ = 3e-3;
  bool was_pressed_ = false;
  std::string attach_object_;
  double attach_abscissa_ = 0.0;
  long grasps_ = 0;
  bool started_ = false;
  bool drives_instrument_ = false;  // built by forInstrument
};

}  // namespace filum::haptics
