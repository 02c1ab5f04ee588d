#include "filum/collision/knot_tightness.hpp"

#include <algorithm>
#include <cmath>

namespace filum::collision {

namespace {

Vec3 pointAt(const Points& line, double position) {
  const int last = static_cast<int>(line.rows()) - 1;
  const int i = std::clamp(static_cast<int>(std::floor(position)), 0, std::max(last - 1, 0));
  const double t = std::clamp(position - i, 0.0, 1.0);
  if (last == 0) return line.row(0).transpose();
  return ((1.0 - t) * line.row(i) + t * line.row(i + 1)).transpose();
}

}  // namespace

double polylineLength(const Points& line, double from, double to) {
  if (to < from) std::swap(from, to);
  const int last = static_cast<int>(line.rows()) - 1;
  from = std::clamp(from, 0.0, static_cast<double>(last));
  to = std::clamp(to, 0.0, static_cast<double>(last));
  // The partial edges at both ends, the whole edges between.
  const int first_vertex = static_cast<int>(std::ceil(from)), last_vertex = static_cast<int>(std::floor(to));
  if (first_vertex > last_vertex) return (pointAt(line, to) - pointAt(line, from)).norm();
  double length = (line.row(first_vertex).transpose() - pointAt(line, from)).norm() +
                  (pointAt(line, to) - line.row(last_vertex).transpose()).norm();
  for (int i = first_vertex; i < last_vertex; ++i) length += (line.row(i + 1) - line.row(i)).norm();
  return length;
}

double atPosition(const std::vector<double>& values, double position) {
  const int last = static_cast<int>(values.size()) - 1;
  if (last <= 0) return last == 0 ? values[0] : 0.0;
  const int i = std::clamp(static_cast<int>(std::floor(position)), 0, last - 1);
  const double t = std::clamp(position - i, 0.0, 1.0);
  return (1.0 - t) * values[i] + t * values[i + 1];
}

KnotTightness knotTightness(const ContactPipeline* pipeline, const CurveBody& body, const Points& line,
                            const std::vector<double>& abscissas, const KnotSpan& span, const SceneState& s) {
  KnotTightness k;
  if (!span.found) return k;
  k.loop_length = polylineLength(line, span.first, span.last);
  if (!pipeline) return k;
  const double s0 = atPosition(abscissas, span.first), s1 = atPosition(abscissas, span.last);
  auto inKnot = [&](double abscissa) { return abscissa >= std::min(s0, s1) && abscissa <= std::max(s0, s1); };
  const ContactSet& contacts = pipeline->contacts();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (c.againstObstacle() || c.model_b < 0) continue;
    if (&pipeline->models()[c.model_a]->curve() != &body || &pipeline->models()[c.model_b]->curve() != &body) continue;
    if (!inKnot(c.a.abscissa()) || !inKnot(c.b.abscissa())) continue;
    ++k.contacts;
    k.contact_force += pipeline->contactForce(static_cast<int>(i), s).norm();
    const ContactKinematics kin = contactKinematics(c, s);
    const Vec3 relative = kin.v_a - kin.v_b;
    const Vec3 tangential = relative - c.normal * c.normal.dot(relative);  // (I − n nᵀ)(v_A − v_B)
    k.slip_speed = std::max(k.slip_speed, tangential.norm());
  }
  return k;
}

}  // namespace filum::collision
