#include "filum/haptics/trainee_metrics.hpp"

#include <cmath>
#include <sstream>

namespace filum::haptics {

double InstrumentTally::economy() const {
  if (!(path_length > 0.0)) return 1.0;
  return (last - start).norm() / path_length;
}

void TraineeMetrics::addInstrument(const std::string& name, const std::string& kind) {
  InstrumentTally tally;
  tally.name = name;
  tally.kind = kind;
  instruments_.push_back(tally);
}

void TraineeMetrics::sample(int i, double h, const Vec3& tip, double opening, double force, double force_limit) {
  InstrumentTally& m = instruments_[i];
  if (!m.sampled) {
    m.start = m.last = tip;
    m.last_opening = opening;
    m.sampled = true;
  }
  const double moved = (tip - m.last).norm();
  m.path_length += moved;
  const bool tip_moving = moved > idle_speed_ * h;
  // The jaws opening or closing at a tenth of full travel per second count as motion too.
  const bool jaws_moving = std::abs(opening - m.last_opening) > 0.1 * h;
  if (!tip_moving && !jaws_moving) m.idle_time += h;
  if (tip_moving) moving_ = true;
  m.last = tip;
  m.last_opening = opening;
  m.max_force = std::max(m.max_force, force);
  m.force_integral += force * h;
  if (force > force_limit) m.time_above_limit += h;
}

nlohmann::json TraineeMetrics::summary() const {
  nlohmann::json out;
  out["task_time"] = taskTime();
  out["duration"] = duration_;
  out["idle_speed"] = idle_speed_;
  out["instrument_contacts"] = tool_contacts_;
  out["thread_breaks"] = breaks_;
  if (removed_length_ >= 0.0) out["removed_length"] = removed_length_;
  if (inspected_length_ >= 0.0) {
    out["inspected_length"] = inspected_length_;
    out["inspected_fraction"] = inspected_fraction_;
  }
  nlohmann::json list = nlohmann::json::array();
  for (const InstrumentTally& m : instruments_) {
    list.push_back({{"name", m.name},
                    {"type", m.kind},
                    {"path_length", m.path_length},
                    {"economy", m.economy()},
                    {"idle_time", m.idle_time},
                    {"grasps", m.grasps},
                    {"regrasps", m.regrasps},
                    {"missed_grasps", m.missed_grasps},
                    {"slip_length", m.slip_length},
                    {"max_force", m.max_force},
                    {"mean_force", duration_ > 0.0 ? m.force_integral / duration_ : 0.0},
                    {"time_above_force_limit", m.time_above_limit},
                    {"cuts", m.cuts},
                    {"cuts_coagulated", m.cuts_coagulated},
                    {"cuts_refused", m.cuts_refused},
                    {"coagulations", m.coagulations}});
  }
  out["instruments"] = list;
  return out;
}

std::string TraineeMetrics::text() const {
  std::ostringstream out;
  out.precision(3);
  out << "metrics: task time " << taskTime() << " s, " << tool_contacts_ << " instrument contacts, " << breaks_
      << " thread breaks";
  if (removed_length_ >= 0.0) out << ", specimen " << 1e3 * removed_length_ << " mm removed";
  if (inspected_length_ >= 0.0)
    out << ", inspected " << 1e3 * inspected_length_ << " mm (" << 100.0 * inspected_fraction_ << " % of the length)";
  out << '\n';
  for (const InstrumentTally& m : instruments_) {
    out << "  " << m.name << " (" << m.kind << "): path " << 1e3 * m.path_length << " mm, economy " << m.economy()
        << ", idle " << m.idle_time << " s, grasps " << m.grasps << " (regrasps " << m.regrasps << ", missed "
        << m.missed_grasps << "), max force " << m.max_force << " N, above limit " << m.time_above_limit << " s";
    if (m.cuts + m.cuts_refused > 0)
      out << ", cuts " << m.cuts << " (coagulated " << m.cuts_coagulated << ", refused " << m.cuts_refused << ")";
    if (m.coagulations > 0) out << ", coagulations " << m.coagulations;
    out << '\n';
  }
  return out.str();
}

}  // namespace filum::haptics
