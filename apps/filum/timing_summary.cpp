#include "filum/timing_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

namespace filum::app {

TimingSummary TimingSummary::fromStepTimes(const std::vector<double>& step_seconds, double dt, double wall) {
  TimingSummary t;
  t.steps = static_cast<long>(step_seconds.size());
  t.dt = dt;
  t.simulated = t.steps * dt;
  t.wall = wall;
  if (step_seconds.empty()) return t;
  std::vector<double> sorted = step_seconds;
  std::sort(sorted.begin(), sorted.end());
  t.step_wall = std::accumulate(sorted.begin(), sorted.end(), 0.0);
  // One step covers dt seconds = 1000 dt simulated ms; wall ms per simulated ms = wall / dt.
  const double scale = 1.0 / dt;
  const std::size_t n = sorted.size();
  const double median = n % 2 ? sorted[n / 2] : 0.5 * (sorted[n / 2 - 1] + sorted[n / 2]);
  t.per_sim_ms_min = sorted.front() * scale;
  t.per_sim_ms_median = median * scale;
  t.per_sim_ms_max = sorted.back() * scale;
  t.per_sim_ms_mean = t.step_wall / t.simulated;
  return t;
}

std::string TimingSummary::text() const {
  char buffer[512];
  std::snprintf(buffer, sizeof buffer,
                "steps: %ld of dt = %g s, simulated %.6g s in %.3f s wall (%.3f s stepping)\n"
                "wall time per simulated ms: median %.4g ms, min %.4g ms, max %.4g ms, mean %.4g ms "
                "(real time needs <= 1)\n",
                steps, dt, simulated, wall, step_wall, per_sim_ms_median, per_sim_ms_min, per_sim_ms_max,
                per_sim_ms_mean);
  std::string text = buffer;
  if (contact.solves > 0) {
    std::snprintf(buffer, sizeof buffer,
                  "contact solves: %ld, %.4g %% converged (residual below tolerance), %ld fell back to Gauss-Seidel, "
                  "%.3g iterations each on average (%.3g of them on an earlier factorization), worst residual "
                  "%.3g x the tolerance\n",
                  contact.solves, 100.0 * contact.converged / contact.solves, contact.fell_back,
                  static_cast<double>(contact.iterations) / contact.solves,
                  static_cast<double>(contact.chord_steps) / contact.solves, contact.worst_ratio);
    text += buffer;
  }
  if (step_wall > 0.0) {
    // The shares of the steps' time; "rest": between the stages (state copies, end-of-step checks).
    const double share = 100.0 / step_wall;
    std::snprintf(buffer, sizeof buffer,
                  "time by stage: collision detection %.3g %%, integration (forces, step matrix, its solves) %.3g %%, "
                  "constraint and contact solve %.3g %%, missed-contact check %.3g %%, layout changes %.3g %%, "
                  "rest %.3g %%\n",
                  stages.detection * share, stages.integration * share, stages.constraint_solve * share,
                  stages.missed_contact * share, stages.layout * share, std::max(0.0, step_wall - stages.total()) * share);
    text += buffer;
  }
  return text;
}

std::string TimingSummary::json() const {
  char buffer[1024];
  std::snprintf(buffer, sizeof buffer,
                "{\n  \"steps\": %ld,\n  \"dt_s\": %.17g,\n  \"simulated_s\": %.17g,\n  \"wall_s\": %.6f,\n"
                "  \"step_wall_s\": %.6f,\n  \"wall_ms_per_simulated_ms\": {\"median\": %.6g, \"min\": %.6g, "
                "\"max\": %.6g, \"mean\": %.6g},\n  \"contact_solves\": {\"solves\": %ld, \"converged\": %ld, "
                "\"fell_back\": %ld, \"iterations\": %ld, \"chord_steps\": %ld, \"worst_residual_over_tolerance\": %.6g},\n"
                "  \"stages_s\": {\"collision_detection\": %.6f, \"integration\": %.6f, \"constraint_solve\": %.6f, "
                "\"missed_contact_check\": %.6f, \"layout\": %.6f}\n}\n",
                steps, dt, simulated, wall, step_wall, per_sim_ms_median, per_sim_ms_min, per_sim_ms_max,
                per_sim_ms_mean, contact.solves, contact.converged, contact.fell_back, contact.iterations, contact.chord_steps,
                std::isfinite(contact.worst_ratio) ? contact.worst_ratio : -1.0, stages.detection, stages.integration,
                stages.constraint_solve, stages.missed_contact, stages.layout);
  return buffer;
}

}  // namespace filum::app
