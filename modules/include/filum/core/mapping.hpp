// Mapping: child = f(parent), joining the mechanical side to the collision and visual sides
// (docs/architecture.md, "The three-sided model"). For a spline P(s) = Σ b_i(s) q_i the Jacobian
// row of a point at abscissa s holds the basis values b_i(s), so a force F at s adds b_i(s) F to
// control point i (paper §3).
//
// A mapping is an interface, not a scene component: the models that need one own it (a collision
// model its sphere sampling, a visual its axis samples), and every point at which a force acts
// holds one (BodyPoint, the mapping of one point: the route of every force from a point of a
// curve to the control points).
#pragma once

#include <string>

#include "filum/core/types.hpp"

namespace filum {

class Mapping {
 public:
  virtual ~Mapping() = default;

  virtual std::string typeName() const = 0;
  virtual int inputCount() const = 0;   // parent points
  virtual int outputCount() const = 0;  // child points

  /// out = f(in): positions down.
  virtual void apply(ConstPointsRef in, PointsRef out) const = 0;
  /// v_out = J(in) v_in: velocities down.
  virtual void applyJ(ConstPointsRef in, ConstPointsRef v_in, PointsRef v_out) const = 0;
  /// f_in += J(in)ᵀ f_out: forces up (accumulates).
  virtual void applyJT(ConstPointsRef in, ConstPointsRef f_out, PointsRef f_in) const = 0;
  /// J(in), (3·outputCount) × (3·inputCount), coordinates interleaved x y z per point.
  virtual SparseMatrix jacobian(ConstPointsRef in) const = 0;
};

}  // namespace filum
