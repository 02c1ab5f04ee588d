// Contact: one entry of a step's contact set — a point of a thread (A) against a point of another
// or the same thread, or against an obstacle surface (B).
//
// Points of threads are weights on control points (PointWeights: the basis values at a sphere
// centre, or a blend of two rows on the chord between centres), so every contact quantity maps
// to the DOFs through the Jacobian row of its point (paper §3: "forces can be applied on any
// point of the spline"; docs/architecture.md, "The three-sided model"). The contact is linearized
// over the step, as contacts are in SOFA or Bullet: the normal n (unit, from B towards A) and the
// chord parameters are those found at the step's start; only positions and velocities change
// between integrator stages. The gap, positive when apart,
//   g(q, t) = n·(x_A(q) − x_B(q, t)) − R,   R = r_A + r_B (thread–thread), r_A (thread–obstacle),
// with x_B(t) = p_0 + v_B (t − t_0) for an obstacle (surface point p_0 moving with the surface
// velocity v_B), has the constant gradient ∂g/∂q_j = w_{A,j} n − w_{B,j} n, and
//   ġ = n·(v_A − v_B).
#pragma once

#include <vector>

#include "filum/collision/sphere_sampling_mapping.hpp"
#include "filum/core/scene_state.hpp"

namespace filum::collision {

struct Contact {
  // Thread side A (always a thread): weights on its body's control points, whose first point is
  // at global index offset_a.
  int model_a = 0;
  int offset_a = 0;
  PointWeights a;
  double abscissa_a = 0.0;  // s of the contact point on A's spline (for reports)

  // Side B: another thread point (model_b >= 0), or an obstacle (obstacle >= 0).
  int model_b = -1;
  int offset_b = 0;
  PointWeights b;
  double abscissa_b = 0.0;
  int obstacle = -1;
  Vec3 surface_point = Vec3::Zero();     // p_0 (m) at time t_0
  Vec3 surface_velocity = Vec3::Zero();  // v_B (m/s)
  double time = 0.0;                     // t_0 (s)

  Vec3 normal = Vec3::UnitZ();  // n, unit, from B towards A
  double radius = 0.0;          // R (m)
  double friction = 0.0;        // Coulomb μ

  bool againstObstacle() const { return obstacle >= 0; }
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

/// B += J_cᵀ F: +F at point A, −F at point B (nothing at an obstacle), through the weights.
void addContactForce(const Contact& c, const Vec3& F, VecX& B);

/// The contact set of one step, in a deterministic order (thread–obstacle contacts by model,
/// obstacle and sphere, then thread–thread contacts by sorted broad-phase pair).
using ContactSet = std::vector<Contact>;

}  // namespace filum::collision
