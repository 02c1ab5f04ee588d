// TraineeMetrics: how an instrument was used, in the terms trainers score laparoscopic and
// suturing skills by (motion analysis as in ICSAD and the simulators' reports: time, path
// length, economy of motion, idle time; errors: excessive force, missed and repeated grasps,
// cuts outside a coagulated span, instruments clashing, a thread broken).
//
// Per instrument, from its tip (instrument_shape.hpp) sampled at every step:
//   path length    Σ |x_tip(t_k+1) − x_tip(t_k)| (m);
//   economy        |x_tip(end) − x_tip(start)| / path length (1: a straight move; no motion: 1);
//   idle time      the time the tip moved slower than idle_speed (default 5 mm/s) while the
//                  jaws did not move either (s);
//   grasps, regrasps (a grasp of a body this instrument had let go of before), missed grasps
//                  (jaws closed on nothing), slips (length of thread that slid through, m);
//   force on tissue |F| = |the hold's coupling force| + |the contact force of its parts| (N):
//                  max, mean over the run, time above force_limit (s);
//   cuts, of them inside a coagulated span, refused (outside one, when required), coagulations.
// For the run: task time (from the first to the last step in which some tip moved faster than
// idle_speed), instrument–instrument contacts (onsets of two parts of different instruments
// closer than their radii), thread breaks.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/types.hpp"

namespace filum::haptics {

struct InstrumentTally {
  std::string name, kind;
  double path_length = 0.0;
  Vec3 start = Vec3::Zero(), last = Vec3::Zero();
  bool sampled = false;
  double last_opening = 0.0;
  double idle_time = 0.0;
  int grasps = 0, regrasps = 0, missed_grasps = 0;
  double slip_length = 0.0;
  double max_force = 0.0, force_integral = 0.0, time_above_limit = 0.0;
  int cuts = 0, cuts_coagulated = 0, cuts_refused = 0, coagulations = 0;
  double economy() const;
};

class TraineeMetrics {
 public:
  explicit TraineeMetrics(double idle_speed = 5e-3) : idle_speed_(idle_speed) {}
  void addInstrument(const std::string& name, const std::string& kind);
  InstrumentTally& instrument(int i) { return instruments_[i]; }
  const InstrumentTally& instrument(int i) const { return instruments_[i]; }
  int instrumentCount() const { return static_cast<int>(instruments_.size()); }

  /// One step of length h: instrument i's tip and jaw opening at its end, force on tissue and
  /// force limit.
  void sample(int i, double h, const Vec3& tip, double opening, double force, double force_limit);
  /// Instrument i at the start: its tip and jaw opening.
  void start(int i, const Vec3& tip, double opening) {
    InstrumentTally& m = instruments_[i];
    m.start = m.last = tip;
    m.last_opening = opening;
    m.sampled = true;
  }
  /// After every instrument's sample of the step of length h ending at t: the task runs from the
  /// start of the first step in which a tip moved to the end of the last.
  void endStep(double t, double h) {
    if (moving_) {
      if (first_motion_ < 0.0) first_motion_ = t - h;
      last_motion_ = t;
    }
    moving_ = false;
    duration_ = t;
  }
  void countToolContact() { ++tool_contacts_; }
  /// The specimen's length (m): the curve cut off the end kept in the patient (InstrumentSet's
  /// "specimen"); reported when set at least once.
  void setRemovedLength(double length) { removed_length_ = length; }
  /// −1 when the scene names no specimen.
  double removedLength() const { return removed_length_; }
  /// The length that passed between the graspers (m) and its fraction of the body (InstrumentSet's
  /// "inspection", grasp_coverage.hpp); reported when set at least once.
  void setInspected(double length, double fraction) {
    inspected_length_ = length;
    inspected_fraction_ = fraction;
  }
  double inspectedFraction() const { return inspected_fraction_; }
  void countBreak() { ++breaks_; }

  double idleSpeed() const { return idle_speed_; }
  double taskTime() const { return first_motion_ < 0.0 ? 0.0 : last_motion_ - first_motion_; }
  int toolContacts() const { return tool_contacts_; }
  int breaks() const { return breaks_; }

  /// The summary (metrics.json) and as lines for the run's log.
  nlohmann::json summary() const;
  std::string text() const;

 private:
  double idle_speed_;
  std::vector<InstrumentTally> instruments_;
  bool moving_ = false;
  double first_motion_ = -1.0, last_motion_ = 0.0, duration_ = 0.0;
  int tool_contacts_ = 0, breaks_ = 0;
  double removed_length_ = -1.0;
  double inspected_length_ = -1.0, inspected_fraction_ = -1.0;
};

}  // namespace filum::haptics
