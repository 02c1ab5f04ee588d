#include "filum/core/curve_body.hpp"

#include <algorithm>

namespace filum {

namespace {
// Σ_j w_j q_{first + j} over the row's support, q this body's block of the state.
template <typename Weights>
Vec3 combine(const BasisRow& row, const Weights& w, ConstPointsMap q) {
  Vec3 p = Vec3::Zero();
  for (int j = 0; j < row.count; ++j) p += w[j] * q.row(row.first + j).transpose();
  return p;
}
}  // namespace

std::vector<double> CurveBody::sectionAbscissas() const {
  if (!radiusVaries() && !innerRadiusVaries()) return {0.0};
  const std::vector<double> breaks = basis().breakpoints();
  std::vector<double> at;
  at.reserve(2 * breaks.size());
  for (std::size_t i = 0; i < breaks.size(); ++i) {
    at.push_back(breaks[i]);
    if (i + 1 < breaks.size()) at.push_back(0.5 * (breaks[i] + breaks[i + 1]));
  }
  return at;
}

CurveBody::RadiusRange CurveBody::radiusRange() const {
  RadiusRange range{radius(), radius()};
  if (!radiusVaries()) return range;
  range.smallest = range.largest = radiusAt(0.0);
  for (const double s : sectionAbscissas()) {
    const double r = radiusAt(s);
    range.smallest = std::min(range.smallest, r);
    range.largest = std::max(range.largest, r);
  }
  return range;
}

namespace {

/// Times of one list of scheduled changes: >= 0 and increasing (entry `item` of `what`).
double scheduledTime(const Params& item, const std::vector<double>& earlier, const char* what) {
  const double time = item.number({"time", "s"});
  if (!(time >= 0.0)) item.fail("time", "a time >= 0 (s)");
  if (!earlier.empty() && !(time > earlier.back()))
    item.fail("time", std::string("a time later than the previous ") + what + "'s (" + describeJson(earlier.back()) + " s)");
  return time;
}

}  // namespace

std::vector<CurveBody::LayoutChange> CurveBody::layoutChangesFromParams(const Params& p) {
  std::vector<LayoutChange> out;
  std::vector<double> times;
  if (p.has("refine"))
    for (const Params& item : p.objects("refine")) {
      LayoutChange r;
      r.time = scheduledTime(item, times, "refinement");
      times.push_back(r.time);
      const nlohmann::json& list = item.raw({"abscissas", "1"});
      if (!list.is_array() || list.empty()) item.fail("abscissas", "a non-empty array of abscissas in (0, 1)");
      for (std::size_t k = 0; k < list.size(); ++k) {
        if (!list[k].is_number() || !(list[k].get<double>() > 0.0 && list[k].get<double>() < 1.0))
          item.fail("abscissas", "abscissas strictly inside (0, 1)", "entry " + std::to_string(k) + ": " + list[k].dump());
        r.abscissas.push_back(list[k].get<double>());
      }
      item.finish();
      out.push_back(std::move(r));
    }
  times.clear();
  if (p.has("cuts"))
    for (const Params& item : p.objects("cuts")) {
      LayoutChange c;
      c.kind = LayoutChange::Kind::kCut;
      c.time = scheduledTime(item, times, "cut");
      times.push_back(c.time);
      const double s = item.number({"abscissa", "1"});
      if (!(s > 0.0 && s < 1.0)) item.fail("abscissa", "an abscissa strictly inside (0, 1) to cut at");
      c.abscissas.push_back(s);
      item.finish();
      out.push_back(std::move(c));
    }
  // One schedule: by time, insertions before cuts at equal times (stable: refine came first).
  std::stable_sort(out.begin(), out.end(), [](const LayoutChange& a, const LayoutChange& b) { return a.time < b.time; });
  return out;
}

Vec3 CurveBody::position(const VecX& q, double s) const {
  BasisRow r;
  row(s, r);
  return combine(r, r.value, block(q));  // P(s) = Σ b_j(s) q_j
}

Vec3 CurveBody::tangent(const VecX& q, double s) const {
  BasisRow r;
  row(s, r);
  return combine(r, r.d1, block(q));  // P'(s)
}

Vec3 CurveBody::secondDerivative(const VecX& q, double s) const {
  BasisRow r;
  row(s, r);
  return combine(r, r.d2, block(q));  // P''(s)
}

}  // namespace filum
