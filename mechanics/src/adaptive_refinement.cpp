#include "filum/mechanics/adaptive_refinement.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::mechanics {

std::unique_ptr<AdaptiveRefinement> AdaptiveRefinement::fromParams(const Params& p) {
  Settings s;
  s.every = p.integer("every", 1, 1000000, 10, "steps between plans");
  s.refine_angle = p.positive({"refine_angle", "rad"}, s.refine_angle);
  if (s.refine_angle > M_PI) p.fail("refine_angle", "a turning angle in (0, π] rad", std::to_string(s.refine_angle));
  s.coarsen_angle = p.nonNegative({"coarsen_angle", "rad"}, std::min(s.coarsen_angle, s.refine_angle / 4.0));
  if (s.coarsen_angle > s.refine_angle / 4.0)
    p.fail("coarsen_angle",
           "at most refine_angle / 4 = " + std::to_string(s.refine_angle / 4.0) +
               " rad (the halves of a span just split must not be merged again)",
           std::to_string(s.coarsen_angle));
  s.min_span = p.nonNegative({"min_span", "m"}, 0.0);
  s.tolerance = p.positive({"tolerance", "m"}, s.tolerance);
  s.max_points = p.integer("max_points", 4, kMaxControlPoints, 0, "a body's control points at most (dynamic_spline.hpp)");
  s.min_points = p.integer("min_points", 4, kMaxControlPoints, 0, "a body's control points at most (dynamic_spline.hpp)");
  if (s.max_points > 0 && s.min_points > s.max_points)
    p.fail("min_points", "at most max_points (" + std::to_string(s.max_points) + ")", std::to_string(s.min_points));
  return std::make_unique<AdaptiveRefinement>(s);
}

void AdaptiveRefinement::init(const Scene&) {
  curve_ = body().curve();
  if (!curve_ || body().internalVelocityCount() > 0)
    throw SceneError(origin(), "a curve body whose control points are its only DOFs (a spline) for " + describe(),
                     body().describe());
  // Bound at init and again after every layout change: the limits come from the first binding.
  if (max_points_ == 0) {
    const int n = curve_->pointCount();
    max_points_ = settings_.max_points > 0 ? settings_.max_points : std::min(2 * n, kMaxControlPoints);
    min_points_ = settings_.min_points > 0 ? settings_.min_points : n;
    if (min_points_ > max_points_)
      throw SceneError(origin(), "min_points (" + std::to_string(min_points_) + ") at most max_points",
                       std::to_string(max_points_));
    const std::size_t room = static_cast<std::size_t>(max_points_) + 8;
    for (auto* v : {&breakpoints_, &angles_, &lengths_, &acting_}) v->reserve(room);
    touched_.reserve(room);
    removed_.reserve(room);
    order_.reserve(room);
    refused_.reserve(room);
    planned_turning_.reserve(room);
  }
  // Bound again after every layout change (Scene::relayout): the breakpoints are read here, in
  // the step that changed the layout, so that a plan that changes nothing allocates nothing.
  layout_revision_ = -1;
  refreshLayout();
}

void AdaptiveRefinement::refreshLayout() const {
  if (curve_->layoutRevision() == layout_revision_) return;
  layout_revision_ = curve_->layoutRevision();
  breakpoints_ = curve_->basis().breakpoints();
  cuts_ = curve_->basis().cuts();
  // Refusals of knots that are knots no longer are forgotten; the others stand (their spans'
  // turning decides when they are tried again).
  refused_.erase(std::remove_if(refused_.begin(), refused_.end(),
                                [&](const std::pair<double, double>& r) {
                                  return !std::binary_search(breakpoints_.begin(), breakpoints_.end(), r.first);
                                }),
                 refused_.end());
}

void AdaptiveRefinement::plan(const Scene& scene, Plan& out) const {
  refreshLayout();
  const VecX& q = scene.state().q;
  const int spans = static_cast<int>(breakpoints_.size()) - 1;
  angles_.assign(spans, 0.0);
  lengths_.assign(spans, 0.0);
  touched_.assign(spans, 0);
  // θ_k and ℓ_k over 4 pieces of each span (at a cut the strand's own ends: the left limits).
  constexpr int kPieces = 4;
  for (int k = 0; k < spans; ++k) {
    const double a = breakpoints_[k], b = breakpoints_[k + 1];
    Vec3 last_point = curve_->position(q, a), last_tangent = curve_->tangent(q, a);
    for (int i = 1; i <= kPieces; ++i) {
      const double s = i == kPieces ? b - 1e-12 * (b - a) : a + (b - a) * i / kPieces;
      const Vec3 point = curve_->position(q, s), tangent = curve_->tangent(q, s);
      lengths_[k] += (point - last_point).norm();
      const double norms = last_tangent.norm() * tangent.norm();
      if (norms > 0.0) angles_[k] += std::atan2(last_tangent.cross(tangent).norm(), last_tangent.dot(tangent));
      last_point = point;
      last_tangent = tangent;
    }
  }
  acting_.clear();
  scene.actingAbscissas(body(), acting_);
  for (const double s : acting_) {
    const auto it = std::upper_bound(breakpoints_.begin(), breakpoints_.end(), s);
    const int k = std::clamp(static_cast<int>(it - breakpoints_.begin()) - 1, 0, spans - 1);
    touched_[k] = 1;
  }
  // Insertions: bent spans (largest angle first), then touched spans longer than min_span.
  int count = curve_->pointCount();
  order_.clear();
  for (int k = 0; k < spans; ++k)
    if (angles_[k] > settings_.refine_angle || (touched_[k] && settings_.min_span > 0.0 && lengths_[k] > 2.0 * settings_.min_span))
      order_.push_back(k);
  std::sort(order_.begin(), order_.end(), [&](int x, int y) { return angles_[x] > angles_[y] || (angles_[x] == angles_[y] && x < y); });
  for (const int k : order_) {
    if (count >= max_points_) break;
    out.insert.push_back(0.5 * (breakpoints_[k] + breakpoints_[k + 1]));
    ++count;
  }
  std::sort(out.insert.begin(), out.insert.end());
  // Removals: interior knots between two straight, untouched spans not being split, none next to
  // a cut or to another knot removed now.
  removed_.assign(spans + 1, 0);
  planned_turning_.clear();
  const auto atCut = [&](double s) {
    for (const double c : cuts_)
      if (std::abs(c - s) <= 1e-12) return true;
    return false;
  };
  for (int j = 1; j < spans && count > min_points_; ++j) {
    const bool straight = angles_[j - 1] < settings_.coarsen_angle && angles_[j] < settings_.coarsen_angle;
    if (!straight || touched_[j - 1] || touched_[j] || removed_[j - 1]) continue;
    if (atCut(breakpoints_[j]) || atCut(breakpoints_[j - 1]) || atCut(breakpoints_[j + 1])) continue;
    bool splitting = false;
    for (const double s : out.insert) splitting = splitting || (s > breakpoints_[j - 1] && s < breakpoints_[j + 1]);
    if (splitting) continue;
    const double turning = angles_[j - 1] + angles_[j];
    bool refused_before = false;
    for (const auto& r : refused_) refused_before = refused_before || (r.first == breakpoints_[j] && turning > 0.5 * r.second);
    if (refused_before) continue;
    out.remove.push_back(breakpoints_[j]);
    planned_turning_.emplace_back(breakpoints_[j], turning);
    removed_[j] = 1;
    --count;
  }
  out.tolerance = settings_.tolerance;
}

void AdaptiveRefinement::removalRefused(double abscissa) {
  double turning = 0.0;
  for (const auto& p : planned_turning_)
    if (p.first == abscissa) turning = p.second;
  for (auto& r : refused_)
    if (r.first == abscissa) {
      r.second = turning;
      return;
    }
  if (refused_.size() < refused_.capacity()) refused_.emplace_back(abscissa, turning);
}

}  // namespace filum::mechanics
