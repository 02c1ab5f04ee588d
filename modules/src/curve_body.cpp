#include "filum/core/curve_body.hpp"

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

std::vector<CurveBody::Refinement> CurveBody::refinementsFromParams(const Params& p, const std::string& key) {
  std::vector<Refinement> out;
  if (!p.has(key)) return out;
  for (const Params& item : p.objects(key)) {
    Refinement r;
    r.time = item.number("time");
    if (!(r.time >= 0.0)) item.fail("time", "a time >= 0 (s)");
    if (!out.empty() && !(r.time > out.back().time))
      item.fail("time", "a time later than the previous refinement's (" + describeJson(out.back().time) + " s)");
    const nlohmann::json& list = item.raw("abscissas");
    if (!list.is_array() || list.empty()) item.fail("abscissas", "a non-empty array of abscissas in (0, 1)");
    for (std::size_t k = 0; k < list.size(); ++k) {
      if (!list[k].is_number() || !(list[k].get<double>() > 0.0 && list[k].get<double>() < 1.0))
        item.fail("abscissas", "abscissas strictly inside (0, 1)", "entry " + std::to_string(k) + ": " + list[k].dump());
      r.abscissas.push_back(list[k].get<double>());
    }
    item.finish();
    out.push_back(std::move(r));
  }
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
