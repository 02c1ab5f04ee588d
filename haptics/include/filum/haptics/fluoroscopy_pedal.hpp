// FluoroscopyPedal: when the X-ray is on. An interventionalist sees the wires only while pressing
// the fluoroscopy pedal, and the time it is pressed (the fluoroscopy time) is what trainers score
// of the dose: the patient's and the staff's radiation grows with it. Between presses the monitor
// holds the last image (last-image hold).
// Scene: the top-level "fluoroscopy" block (its imaging settings: visual/fluoroscopy_view.hpp):
//   "fluoroscopy": {"on": [[0.0, 2.5], [3.0, 6.0]]}   // s: the pedal pressed over these spans
// sorted and disjoint; without "on" the pedal is pressed for the whole run. `filum view` presses
// it with a key instead (press / release).
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace filum::haptics {

class FluoroscopyPedal {
 public:
  /// The scene's "fluoroscopy" block's pedal, or nullptr when it has no such block. Throws
  /// SceneError naming the place (spans not [t0, t1] with 0 <= t0 < t1, unsorted, overlapping).
  static std::unique_ptr<FluoroscopyPedal> fromScene(const nlohmann::json& document, const std::string& source);
  /// Pressed for the whole run (no "on" spans).
  FluoroscopyPedal() = default;
  explicit FluoroscopyPedal(std::vector<std::pair<double, double>> spans);

  /// Pressed at time t (s): a scripted span holds t0 <= t < t1, or the last press() of a hand.
  bool on(double t) const;
  /// The fluoroscopy time up to t (s): how long the pedal was pressed over [0, t].
  double time(double t) const;

  /// By hand (`filum view`): pressed or released at time t; scripted spans are then ignored.
  void press(double t);
  void release(double t);

 private:
  std::vector<std::pair<double, double>> spans_;  // empty: always on (until a hand takes it)
  bool by_hand_ = false;
  bool pressed_ = false;
  double pressed_since_ = 0.0, hand_time_ = 0.0;
};

}  // namespace filum::haptics
