#include "filum/collision/penalty_contact.hpp"

#include <algorithm>

#include <Eigen/Geometry>

namespace filum::collision {

PenaltyForce penaltyForce(const Contact& c, const ContactKinematics& k, const PenaltyLaw& law) {
  PenaltyForce out;
  if (k.gap >= 0.0) return out;
  // f_n = max(0, −k g − c ġ): a spring and a damper that only push.
  out.normal = std::max(0.0, -law.stiffness * k.gap - law.damping * k.gap_rate);
  out.force = out.normal * c.normal;
  if (c.friction > 0.0 && out.normal > 0.0) {
    // F_t = −μ f_n v_t / max(|v_t|, ε)
    const Vec3 v_t = (k.v_a - k.v_b) - k.gap_rate * c.normal;
    out.force -= (c.friction * out.normal / std::max(v_t.norm(), law.friction_velocity)) * v_t;
  }
  return out;
}

void addPenaltyJacobian(const Contact& c, const ContactKinematics& k, const PenaltyLaw& law, double k_factor,
                        double d_factor, JacobianAccumulator& out) {
  const PenaltyForce f = penaltyForce(c, k, law);
  if (!(f.normal > 0.0)) return;
  const Vec3& n = c.normal;
  const Vec3 v_t = (k.v_a - k.v_b) - k.gap_rate * n;
  const double speed = v_t.norm();
  const Vec3 phi = c.friction > 0.0 ? Vec3(v_t / std::max(speed, law.friction_velocity)) : Vec3::Zero();
  // K = (n − μ φ)(−k n)ᵀ,  D = (n − μ φ)(−c n)ᵀ − μ f_n Φ P
  const Vec3 lever = n - c.friction * phi;
  Eigen::Matrix3d block = k_factor * (lever * (-law.stiffness * n).transpose()) +
                          d_factor * (lever * (-law.damping * n).transpose());
  if (c.friction > 0.0) {
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - n * n.transpose();
    Eigen::Matrix3d Phi;
    if (speed < law.friction_velocity) {
      Phi = Eigen::Matrix3d::Identity() / law.friction_velocity;
    } else {
      const Vec3 t = v_t / speed;
      Phi = (Eigen::Matrix3d::Identity() - t * t.transpose()) / speed;
    }
    block -= d_factor * c.friction * f.normal * (Phi * P);
  }
  // σ_i σ_j w_i w_j block over the points of A (σ = +1) and B (σ = −1): the mappings' rows.
  auto emit = [&](const BodyPoint& pi, double si, const BodyPoint& pj, double sj) {
    pi.forEachWeight([&](int i, double wi) {
      pj.forEachWeight([&](int j, double wj) { out.addBlock(i, j, (si * sj * wi * wj) * block); });
    });
  };
  emit(c.a, 1.0, c.a, 1.0);
  if (!c.againstObstacle()) {
    emit(c.a, 1.0, c.b, -1.0);
    emit(c.b, -1.0, c.a, 1.0);
    emit(c.b, -1.0, c.b, -1.0);
  }
}

}  // namespace filum::collision
