// Penalty contact response (paper §3–4: "the collision detection is then reduced to spheres
// collision, leading to the response to be calculated by a penalty method and directly integrated
// in the system equations (2)"): a normal spring and damper and regularized Coulomb friction at
// the contact point, mapped to the control points through the point's basis weights.
//
// With g the gap and ġ its rate (contact.hpp), v_r = v_A − v_B, v_t = v_r − ġ n:
//   normal force    f_n = max(0, −k g − c ġ)            when g < 0, else 0   (N)
//   friction        F_t = −μ f_n v_t / max(|v_t|, ε)                         (N)
//   force on A      F = f_n n + F_t,  on B −F;   Q_j += w_{A,j} F − w_{B,j} F.
// The friction is Coulomb's law |F_t| <= μ f_n, regularized below the slip speed ε: there the
// tangential force is viscous, −(μ f_n/ε) v_t, so that a body held by friction creeps at
// v = ε F_drive/(μ f_n) < ε instead of sticking exactly (an explicit integrator needs
// ε >= μ f_n h / (2.78 m_eff) for stability, RK4's real-axis limit).
//
// Jacobian (for implicit integrators), with φ = v_t / max(|v_t|, ε), P = I − n nᵀ, both for
// g < 0 and f_n > 0 (zero otherwise):
//   K = ∂F/∂x_A = (n − μ φ)(−k n)ᵀ
//   D = ∂F/∂v_A = (n − μ φ)(−c n)ᵀ − μ f_n Φ P,  Φ = I/ε (|v_t| < ε),  (I − t tᵀ)/|v_t| (slip, t = v_t/|v_t|)
// and ∂F_A/∂x_B = −K, ∂F_B/∂x_A = −K, ∂F_B/∂x_B = K (same for D).
#pragma once

#include "filum/collision/contact.hpp"
#include "filum/core/jacobian_accumulator.hpp"

namespace filum::collision {

struct PenaltyLaw {
  double stiffness = 100.0;         // k (N/m)
  double damping = 0.0;             // c (N·s/m)
  double friction_velocity = 1e-3;  // ε (m/s) > 0
};

struct PenaltyForce {
  Vec3 force = Vec3::Zero();  // F on A (N)
  double normal = 0.0;        // f_n (N)
};

/// The penalty force of contact c with kinematics k.
PenaltyForce penaltyForce(const Contact& c, const ContactKinematics& k, const PenaltyLaw& law);

/// Appends k_factor·∂Q/∂q + d_factor·∂Q/∂q̇ of the contact's force as global triplets.
void addPenaltyJacobian(const Contact& c, const ContactKinematics& k, const PenaltyLaw& law, double k_factor,
                        double d_factor, JacobianAccumulator& out);

}  // namespace filum::collision
