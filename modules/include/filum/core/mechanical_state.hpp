// MechanicalState: the mechanical side of a body — its degrees of freedom (points in 3D, e.g.
// the control points q_i of a dynamic spline, paper eq. 1) and its mass operator.
//
// The values of the DOFs live in the scene's SceneState (one flat vector for every body);
// a MechanicalState only knows its block [offset, offset + pointCount) of it.
//
// Internal DOFs. A body may have DOFs besides its points: a rod node's rotation, a twist angle.
// They may have more positions than velocities (nq ≠ nv: a unit quaternion, 4 numbers, in q; an
// angular velocity, 3, in v), and they sit after every body's points and the constraints' extra
// DOFs (scene_state.hpp), so that points are laid out alike in q and v and every client that
// works on points (constraints, collision, visual) is unaffected by them. The body declares
// their counts and provides what integrators need of them: q1 = q0 ⊕ w (integrateInternal: move
// positions along a velocity-space increment) and w = q1 ⊖ q0 (differenceInternal), their mass
// operator (solveInternalMass, multiplyInternalMass) and the forces the body itself exerts on them
// (addInternalForce: e.g. the gyroscopic torque −ω × Jω of a rotating frame).
#pragma once

#include "filum/core/component.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/core/types.hpp"

namespace filum {

class CurveBody;

class MechanicalState : public Component {
 public:
  /// The body as a curve (core/curve_body.hpp) when it is one, else null: how constraints,
  /// collision and visual reach a body's curve without naming its type.
  virtual const CurveBody* curve() const { return nullptr; }
  virtual CurveBody* curve() { return nullptr; }

  /// Number of DOF points (control points) of this body.
  virtual int pointCount() const = 0;

  /// Positions the body starts from (m), pointCount() × 3.
  virtual const Points& initialPositions() const = 0;

  /// Velocities the body starts with (m/s), written into `v` (pointCount() × 3); at rest unless
  /// the body says otherwise.
  virtual void initialVelocities(PointsRef v) const { v.setZero(); }

  /// In place B := M⁻¹ B for this body's block (the paper's M A = B solve, eq. 3).
  virtual void solveMass(PointsRef B) const = 0;

  /// out := M x for this body's block.
  virtual void multiplyMass(ConstPointsRef x, PointsRef out) const = 0;

  /// Adds factor·(M ⊗ I₃) into `out` over the scene's global points (offset() + i), for the
  /// matrices of implicit steps. The default builds M column by column from multiplyMass
  /// (O(n²), allocates); bodies with a sparse M override it.
  virtual void addMassMatrix(double factor, JacobianAccumulator& out) const;
  /// Largest |i − j| of control points i, j that a local energy couples (a spline of degree d:
  /// d, its support); the step matrix sizes its band from it. −1: unknown (any width).
  virtual int couplingRange() const { return -1; }

  /// B += generalized gravity forces Q_i = ∫ b_i(s) m g ds (N).
  virtual void addGravity(const Vec3& g, PointsRef B) const = 0;

  /// Gravitational potential energy −∫ m g·P(s) ds (J) at positions q.
  virtual double gravityPotential(const Vec3& g, ConstPointsRef q) const = 0;

  /// Kinetic energy ½ Σ_α (v^α)ᵀ M v^α (J).
  double kineticEnergy(ConstPointsRef v) const;

  // Internal DOFs (see the header). Their blocks: q.segment(internalPositionOffset(), nq),
  // v.segment(internalVelocityOffset(), nv), and the same as v for forces and accelerations.

  /// nq and nv: internal position and velocity values (0 for a body of points only).
  virtual int internalPositionCount() const { return 0; }
  virtual int internalVelocityCount() const { return 0; }
  /// Their values at t = 0 (q: nq, v: nv).
  virtual void initialInternalState(Eigen::Ref<VecX> /*q*/, Eigen::Ref<VecX> /*v*/) const {}
  /// q1 = q0 ⊕ w: the internal positions q0 moved along the velocity-space increment w (nv),
  /// e.g. a unit quaternion turned by the rotation vector w. q1 may alias q0. Default q0 + w,
  /// valid only when nq = nv (a body with nq ≠ nv must override both).
  virtual void integrateInternal(Eigen::Ref<const VecX> q0, Eigen::Ref<const VecX> w, Eigen::Ref<VecX> q1) const {
    q1 = q0 + w;
  }
  /// w = q1 ⊖ q0, the increment that integrateInternal maps q0 to q1 by (error estimates and
  /// tests). Default q1 − q0 (nq = nv only).
  virtual void differenceInternal(Eigen::Ref<const VecX> q1, Eigen::Ref<const VecX> q0, Eigen::Ref<VecX> w) const {
    w = q1 - q0;
  }
  /// B += the generalized forces of the body itself on its internal DOFs at state s (B: the
  /// internal velocity block), e.g. the gyroscopic torque of a rotating frame.
  virtual void addInternalForce(const SceneState& /*s*/, Eigen::Ref<VecX> /*B*/) const {}
  /// In place B := M⁻¹ B and out := M x on the internal velocity block.
  virtual void solveInternalMass(Eigen::Ref<VecX> /*B*/) const {}
  virtual void multiplyInternalMass(Eigen::Ref<const VecX> /*x*/, Eigen::Ref<VecX> out) const { out.setZero(); }

  /// Implicit steps with internal DOFs (a rotation's three velocity components per triple):
  /// adds factor·M of the internal DOFs into `out`, triple k at the global group internalGroup(k)
  /// (JacobianAccumulator's numbering: points first, then internal triples). A body whose
  /// internal DOFs the step matrix cannot hold (nv not a multiple of 3, or no such mass) says so
  /// with supportsImplicitInternal() = false and is refused by implicit integrators.
  virtual bool supportsImplicitInternal() const { return internalVelocityCount() == 0; }
  virtual void addInternalMassMatrix(double /*factor*/, JacobianAccumulator& /*out*/) const {}
  /// Where the step matrix puts the body's point i and internal triple k in the body's band
  /// (slots 0 .. pointCount() + nv/3 − 1): points first by default; a rod interleaves them
  /// (x0, R0, x1, R1, ...) so that its matrix stays a narrow band. couplingRange() counts slots.
  virtual int stepSlotOfPoint(int i) const { return i; }
  virtual int stepSlotOfInternal(int k) const { return pointCount() + k; }
  /// The global group of internal triple k (Scene::init): N + (the body's first triple) + k.
  int internalGroup(int k) const { return internal_group_offset_ + k; }
  void setInternalGroupOffset(int group) { internal_group_offset_ = group; }

  /// Where the internal blocks start in q and in v (set by Scene::init).
  int internalPositionOffset() const { return internal_position_offset_; }
  int internalVelocityOffset() const { return internal_velocity_offset_; }
  void setInternalOffsets(int position, int velocity) {
    internal_position_offset_ = position;
    internal_velocity_offset_ = velocity;
  }
  /// This body's internal block of a position vector (q) or of a velocity-layout vector (v, a, B).
  Eigen::Ref<const VecX> internalPositions(const VecX& q) const {
    return q.segment(internal_position_offset_, internalPositionCount());
  }
  Eigen::Ref<VecX> internalPositions(VecX& q) const { return q.segment(internal_position_offset_, internalPositionCount()); }
  Eigen::Ref<const VecX> internalVelocities(const VecX& v) const {
    return v.segment(internal_velocity_offset_, internalVelocityCount());
  }
  Eigen::Ref<VecX> internalVelocities(VecX& v) const { return v.segment(internal_velocity_offset_, internalVelocityCount()); }

  /// Index of this body's first point in the scene's state (set by Scene::init).
  int offset() const { return offset_; }
  void setOffset(int offset) { offset_ = offset; }

  /// This body's block of a global vector (3N) viewed as points.
  ConstPointsMap block(const VecX& global) const {
    return ConstPointsMap(global.data() + 3 * offset_, pointCount(), 3);
  }
  PointsMap block(VecX& global) const { return PointsMap(global.data() + 3 * offset_, pointCount(), 3); }

 private:
  int offset_ = 0;
  int internal_position_offset_ = 0, internal_velocity_offset_ = 0;
  int internal_group_offset_ = 0;
};

}  // namespace filum
