// GraspCoverage: how much of a body has passed between the graspers — the score of "running the
// bowel", where a surgeon inspects the small bowel by grasping it hand over hand, each grasp a
// short step along it from the last. Consecutive grasps of the body (by any grasper, in time
// order) at abscissas a and b cover the span between them when it is at most `max_step` long
// (measured on the body as it lay at the start); a longer jump skips what lies between. The
// covered spans are merged; the score is their length and its fraction of the body's length.
#pragma once

#include <utility>
#include <vector>

namespace filum::haptics {

class GraspCoverage {
 public:
  /// length_at: the body's length from s = 0 to s = k/(n − 1), k = 0 .. n − 1 (m, n >= 2,
  /// increasing), at the start; max_step (m) the longest step between grasps that counts.
  GraspCoverage(std::vector<double> length_at, double max_step);

  /// A grasp of the body at abscissa s ∈ [0, 1] (after every earlier one).
  void grasp(double abscissa);

  int grasps() const { return grasps_; }
  /// Length covered (m) and its fraction of the body's length.
  double coveredLength() const;
  double fraction() const { return coveredLength() / length_at_.back(); }
  /// The body's length at s (linear between the table's abscissas).
  double lengthAt(double abscissa) const;

 private:
  std::vector<double> length_at_;
  double max_step_;
  int grasps_ = 0;
  double last_ = 0.0;
  std::vector<std::pair<double, double>> spans_;  // covered abscissa spans, disjoint, in order
};

}  // namespace filum::haptics
