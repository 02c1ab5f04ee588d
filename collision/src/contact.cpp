#include "filum/collision/contact.hpp"

namespace filum::collision {

namespace {

Vec3 weighted(const PointWeights& w, int offset, const VecX& x) {
  // Σ_j w_j x_{offset + p_j}
  Vec3 sum = Vec3::Zero();
  for (int j = 0; j < w.count; ++j) sum += w.weight[j] * x.segment<3>(3 * (offset + w.point[j]));
  return sum;
}

}  // namespace

ContactKinematics contactKinematics(const Contact& c, const SceneState& s) {
  ContactKinematics k;
  k.x_a = weighted(c.a, c.offset_a, s.q);
  k.v_a = weighted(c.a, c.offset_a, s.v);
  if (c.againstObstacle()) {
    // x_B(t) = p_0 + v_B (t − t_0)
    k.x_b = c.surface_point + (s.time - c.time) * c.surface_velocity;
    k.v_b = c.surface_velocity;
  } else {
    k.x_b = weighted(c.b, c.offset_b, s.q);
    k.v_b = weighted(c.b, c.offset_b, s.v);
  }
  // g = n·(x_A − x_B) − R,  ġ = n·(v_A − v_B)
  k.gap = c.normal.dot(k.x_a - k.x_b) - c.radius;
  k.gap_rate = c.normal.dot(k.v_a - k.v_b);
  return k;
}

void addContactForce(const Contact& c, const Vec3& F, VecX& B) {
  for (int j = 0; j < c.a.count; ++j) B.segment<3>(3 * (c.offset_a + c.a.point[j])) += c.a.weight[j] * F;
  if (!c.againstObstacle())
    for (int j = 0; j < c.b.count; ++j) B.segment<3>(3 * (c.offset_b + c.b.point[j])) -= c.b.weight[j] * F;
}

}  // namespace filum::collision
