#include "filum/collision/knot_tightness.hpp"

#include <algorithm>
#include <cmath>

#include "filum/geometry/arc_length.hpp"

namespace filum::collision {

bool KnotTightness::allFinite() const {
  return std::isfinite(loop_length) && std::isfinite(contact_force) && std::isfinite(slip_speed);
}

double atPosition(const std::vector<double>& values, double position) {
  const int last = static_cast<int>(values.size()) - 1;
  if (last <= 0) return last == 0 ? values[0] : 0.0;
  const int i = std::clamp(static_cast<int>(std::floor(position)), 0, last - 1);
  const double t = std::clamp(position - i, 0.0, 1.0);
  return (1.0 - t) * values[i] + t * values[i + 1];
}

KnotTightness knotTightness(const ContactPipeline* pipeline, const CurveBody& body, const std::vector<double>& abscissas,
                            const KnotSpan& span, const SceneState& s) {
  KnotTightness k;
  if (!span.found) return k;
  const double s0 = atPosition(abscissas, span.first), s1 = atPosition(abscissas, span.last);
  const geometry::ArcLengthParameterization arc(body.basis(), body.block(s.q));
  k.loop_length = std::abs(arc.lengthAt(s1) - arc.lengthAt(s0));
  if (!pipeline) return k;
  auto inKnot = [&](double abscissa) { return abscissa >= std::min(s0, s1) && abscissa <= std::max(s0, s1); };
  const ContactSet& contacts = pipeline->contacts();
  for (std::size_t i = 0; i < contacts.size(); ++i) {
    const Contact& c = contacts[i];
    if (c.againstObstacle() || c.model_b < 0) continue;
    if (&pipeline->models()[c.model_a]->curve() != &body || &pipeline->models()[c.model_b]->curve() != &body) continue;
    if (!inKnot(c.a.abscissa()) || !inKnot(c.b.abscissa())) continue;
    const Vec3 force = pipeline->contactForce(static_cast<int>(i), s);
    if (!(force.dot(c.normal) > 0.0)) continue;  // within the margin, not pressed
    ++k.contacts;
    k.contact_force += force.norm();
    const ContactKinematics kin = contactKinematics(c, s);
    const Vec3 relative = kin.v_a - kin.v_b;
    const Vec3 tangential = relative - c.normal * c.normal.dot(relative);  // (I − n nᵀ)(v_A − v_B)
    k.slip_speed = std::max(k.slip_speed, tangential.norm());
  }
  return k;
}

}  // namespace filum::collision
