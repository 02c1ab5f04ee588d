#include "filum/haptics/grasp_coverage.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace filum::haptics {

GraspCoverage::GraspCoverage(std::vector<double> length_at, double max_step)
    : length_at_(std::move(length_at)), max_step_(max_step) {
  if (length_at_.size() < 2 || !(length_at_.back() > 0.0))
    throw std::invalid_argument("GraspCoverage: a length table of at least two abscissas and a positive length");
}

double GraspCoverage::lengthAt(double abscissa) const {
  const double at = std::clamp(abscissa, 0.0, 1.0) * static_cast<double>(length_at_.size() - 1);
  const std::size_t below = std::min(static_cast<std::size_t>(at), length_at_.size() - 2);
  const double fraction = at - static_cast<double>(below);
  return (1.0 - fraction) * length_at_[below] + fraction * length_at_[below + 1];
}

void GraspCoverage::grasp(double abscissa) {
  const double s = std::clamp(abscissa, 0.0, 1.0);
  if (grasps_++ > 0 && std::abs(lengthAt(s) - lengthAt(last_)) <= max_step_) {
    // Merge [min, max] of the step into the covered spans.
    double from = std::min(s, last_), to = std::max(s, last_);
    std::vector<std::pair<double, double>> merged;
    merged.reserve(spans_.size() + 1);
    for (const auto& span : spans_) {
      if (span.second < from || span.first > to) {
        merged.push_back(span);
      } else {
        from = std::min(from, span.first);
        to = std::max(to, span.second);
      }
    }
    merged.emplace_back(from, to);
    std::sort(merged.begin(), merged.end());
    spans_ = std::move(merged);
  }
  last_ = s;
}

double GraspCoverage::coveredLength() const {
  double sum = 0.0;
  for (const auto& span : spans_) sum += lengthAt(span.second) - lengthAt(span.first);
  return sum;
}

}  // namespace filum::haptics
