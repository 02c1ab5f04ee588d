#include "filum/collision/contact.hpp"

namespace filum::collision {

ContactKinematics contactKinematics(const Contact& c, const SceneState& s) {
  ContactKinematics k;
  k.x_a = c.a.map(s.q);
  k.v_a = c.a.map(s.v);
  if (c.againstObstacle()) {
    // x_B(t) = p_0 + v_B (t − t_0)
    k.x_b = c.surface_point + (s.time - c.time) * c.surface_velocity;
    k.v_b = c.surface_velocity;
  } else {
    k.x_b = c.b.map(s.q);
    k.v_b = c.b.map(s.v);
  }
  // g = n·(x_A − x_B) − R,  ġ = n·(v_A − v_B)
  k.gap = c.normal.dot(k.x_a - k.x_b) - c.radius;
  k.gap_rate = c.normal.dot(k.v_a - k.v_b);
  return k;
}

void addContactForce(const Contact& c, const Vec3& F, VecX& B) {
  c.a.addForce(F, B);
  if (!c.againstObstacle()) c.b.addForce(F, B, -1.0);
}

}  // namespace filum::collision
