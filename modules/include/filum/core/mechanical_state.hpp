// MechanicalState: the mechanical side of a body — its degrees of freedom (points in 3D, e.g.
// the control points q_i of a dynamic spline, paper eq. 1) and its mass operator.
//
// The values of the DOFs live in the scene's SceneState (one flat vector for every body);
// a MechanicalState only knows its block [offset, offset + pointCount) of it.
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
};

}  // namespace filum
