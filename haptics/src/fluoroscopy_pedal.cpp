#include "filum/haptics/fluoroscopy_pedal.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/params.hpp"

namespace filum::haptics {

std::unique_ptr<FluoroscopyPedal> FluoroscopyPedal::fromScene(const nlohmann::json& document, const std::string& source) {
  if (!document.is_object() || !document.contains("fluoroscopy")) return nullptr;
  const Params p = Params(document, source, "").object("fluoroscopy").withOwner("fluoroscopy");
  if (!p.has("on")) return std::make_unique<FluoroscopyPedal>();
  const nlohmann::json& list = p.raw({"on", "s"});
  // Limits before anything is kept: a pedal pressed more than 10000 times is not a training run.
  if (!list.is_array() || list.size() > 10000)
    p.fail("on", "a list of at most 10000 spans [t0, t1] (s) over which the pedal is pressed", describeJson(list));
  std::vector<std::pair<double, double>> spans;
  for (std::size_t k = 0; k < list.size(); ++k) {
    const nlohmann::json& span = list[k];
    const bool pair = span.is_array() && span.size() == 2 && span[0].is_number() && span[1].is_number();
    const double t0 = pair ? span[0].get<double>() : 0.0, t1 = pair ? span[1].get<double>() : 0.0;
    if (!pair || !std::isfinite(t0) || !std::isfinite(t1) || t0 < 0.0 || !(t1 > t0))
      p.fail("on", "spans [t0, t1] with 0 <= t0 < t1 (s); span " + std::to_string(k) + " is not", describeJson(span));
    if (!spans.empty() && t0 < spans.back().second)
      p.fail("on", "spans sorted in time and disjoint; span " + std::to_string(k) + " starts before the last ends",
             describeJson(span));
    spans.emplace_back(t0, t1);
  }
  return std::make_unique<FluoroscopyPedal>(std::move(spans));
}

FluoroscopyPedal::FluoroscopyPedal(std::vector<std::pair<double, double>> spans) : spans_(std::move(spans)) {
  if (spans_.empty()) spans_.emplace_back(0.0, 0.0);  // an empty "on" list: never pressed
}

bool FluoroscopyPedal::on(double t) const {
  if (by_hand_) return pressed_;
  if (spans_.empty()) return true;
  for (const auto& [t0, t1] : spans_)
    if (t >= t0 && t < t1) return true;
  return false;
}

double FluoroscopyPedal::time(double t) const {
  if (by_hand_) return hand_time_ + (pressed_ ? std::max(0.0, t - pressed_since_) : 0.0);
  if (spans_.empty()) return std::max(0.0, t);
  double total = 0.0;
  for (const auto& [t0, t1] : spans_) total += std::max(0.0, std::min(t, t1) - t0);
  return total;
}

void FluoroscopyPedal::press(double t) {
  if (!by_hand_) {  // the scripted time so far is kept
    hand_time_ = time(t);
    by_hand_ = true;
  } else if (pressed_) {
    return;
  }
  pressed_ = true;
  pressed_since_ = t;
}

void FluoroscopyPedal::release(double t) {
  if (!by_hand_) {
    hand_time_ = time(t);
    by_hand_ = true;
  } else if (pressed_) {
    hand_time_ += std::max(0.0, t - pressed_since_);
  }
  pressed_ = false;
}

}  // namespace filum::haptics
