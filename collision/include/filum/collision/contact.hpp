// Contact: one entry of a step's contact set — a point of a thread (A) against a point of another
// or the same thread, or against an obstacle surface (B).
//
// The points of threads are BodyPoints (core/body_point.hpp): a sphere centre, or a point of the
// chord between two centres, whose mapping row (the basis values there, or two rows blended)
// carries every contact quantity to the DOFs — positions and velocities down, forces up through
// BodyPoint::applyJT (paper §3: "forces can be applied on any point of the spline";
// docs/architecture.md, "The three-sided model"). The contact is linearized over the step, as
// contacts are in SOFA or Bullet: the normal n (unit, from B towards A) and the chord parameters
// are those found at the step's start; only positions and velocities change between integrator
// stages. The gap, positive when apart,
//   g(q, t) = n·(x_A(q) − x_B(q, t)) − R,   R = r_A + r_B (thread–thread), r_A (thread–obstacle),
//                                            −(R_in − r_A) (A inside the lumen of tube B, with n
//                                            towards B's axis: narrow_phase.hpp),
// with x_B(t) = p_0 + v_B (t − t_0) for an obstacle (surface point p_0 moving with the surface
// velocity v_B), has the constant gradient ∂g/∂q_j = w_{A,j} n − w_{B,j} n, and
//   ġ = n·(v_A − v_B).
#pragma once

#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/scene_state.hpp"

namespace filum::collision {

struct Contact {
  // Thread side A (always a thread): the collision model's index and the point on its body.
  int model_a = 0;
  BodyPoint a;

  // Side B: another thread point (model_b >= 0), or an obstacle (obstacle >= 0).
  int model_b = -1;
  BodyPoint b;
  int obstacle = -1;
  Vec3 surface_point = Vec3::Zero();     // p_0 (m) at time t_0
  Vec3 surface_velocity = Vec3::Zero();  // v_B (m/s)
  double time = 0.0;                     // t_0 (s)

  Vec3 normal = Vec3::UnitZ();  // n, unit, from B towards A
  double radius = 0.0;          // R (m)
  double friction = 0.0;        // Coulomb μ

  bool againstObstacle() const { return obstacle >= 0; }
  /// A inside the lumen of tube B (the negative contact distance of that case).
  bool insideLumen() const { return radius < 0.0; }
};

/// Positions, velocities and gap of a contact at a state.
struct ContactKinematics {
  Vec3 x_a, x_b;     // m
  Vec3 v_a, v_b;     // m/s
  double gap = 0.0;  // g (m), < 0 in penetration
  double gap_rate = 0.0;  // ġ (m/s)
};

/// g, ġ and the points of contact c at state s.
ContactKinematics contactKinematics(const Contact& c, const SceneState& s);

/// B += J_cᵀ F: +F at point A, −F at point B (nothing at an obstacle), through their mappings.
void addContactForce(const Contact& c, const Vec3& F, VecX& B);

/// The contact set of one step, in a deterministic order (thread–obstacle contacts by model,
/// obstacle and sphere, then instruments inside tubes by model and sphere, then thread–thread
/// contacts by sorted broad-phase pair).
using ContactSet = std::vector<Contact>;

}  // namespace filum::collision
