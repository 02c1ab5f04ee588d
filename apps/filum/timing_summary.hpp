// TimingSummary: wall-clock cost of a run, per step and per simulated millisecond (the paper's
// figure of merit: "computation time for a simulated time of 1 ms", §5).
#pragma once

#include <string>
#include <vector>

#include "filum/core/constraint_solver.hpp"
#include "filum/core/stage_times.hpp"

namespace filum::app {

struct TimingSummary {
  long steps = 0;
  double dt = 0.0;                 // s
  double simulated = 0.0;          // s
  double wall = 0.0;               // s, whole run including output
  double step_wall = 0.0;          // s, inside Scene::step only
  double per_sim_ms_min = 0.0;     // ms of wall time per simulated ms, per-step statistics
  double per_sim_ms_median = 0.0;
  double per_sim_ms_max = 0.0;
  double per_sim_ms_mean = 0.0;
  ContactSolveTally contact;       // the constraint solver's contact solves (none: solves = 0)
  StageTimes stages;               // s per stage of the steps (Scene::stageTimes)

  /// From per-step wall times (s). Sorts a copy.
  static TimingSummary fromStepTimes(const std::vector<double>& step_seconds, double dt, double wall);
  std::string text() const;
  std::string json() const;
};

}  // namespace filum::app
