// StageTimes: the wall time a scene's steps spent in each stage of the step pipeline
// (DESIGN.md, "The step"), summed since the scene was built — where a scene's time goes, as
// MuJoCo's per-stage timers (mjData.timer) say it for a model. `filum run` reports them
// (timing.json "stages_s", and a line of shares). The stages are exclusive: their sum is the
// steps' time less the bookkeeping between them (copying the state for rollback, the
// end-of-step checks). A StageTimer is two reads of a monotonic clock (~30 ns each here); it
// changes no result.
#pragma once

#include <chrono>

namespace filum {

struct StageTimes {
  double layout = 0.0;             // s: scheduled refinements and cuts, ruptures, adaptive layout
  double detection = 0.0;          // s: collision detection and the force fields' beginStep
  double integration = 0.0;        // s: the integrator's step less the constraint solves in it
  double constraint_solve = 0.0;   // s: the constraints' and contacts' rows and their solve
  double missed_contact = 0.0;     // s: the check that the step's contact set held its motion
  double total() const { return layout + detection + integration + constraint_solve + missed_contact; }
};

/// Adds the wall time from its construction to its destruction to `into` (s).
class StageTimer {
 public:
  explicit StageTimer(double& into) : into_(into), start_(std::chrono::steady_clock::now()) {}
  ~StageTimer() { into_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count(); }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  double& into_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace filum
