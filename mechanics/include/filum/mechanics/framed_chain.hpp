// FramedChain: a chain of point masses, each node with its own rotation — the second body kind of
// the kernel (issue 13), the prototype of the catheter and guidewire rods (discrete Cosserat
// rods: Spillmann & Teschner's CoRdE, Bergou et al.'s discrete elastic rods, Gazzola et al.'s
// Elastica). Node i has a position x_i (a point, m) and an orientation R_i, the rotation from its
// material frame (d1, d2, d3 = R_i e3 along the rod) to the world: a unit quaternion (w, x, y, z)
// in q and the body-frame angular velocity ω_i in v (internal DOFs: 4 positions, 3 velocities per
// node, MechanicalState). Frames move by R ← R exp(h ω) (a right, body-frame increment).
//
// Its centre line is the polyline through the nodes, P(s) = Σ b_i(s) x_i with the degree-1
// B-spline basis on knots at the nodes' rest arc lengths (s ∈ [0, 1]): a CurveBody, so
// constraints, contacts, tools and skins act on it through their existing code.
//
// Mass, lumped (the rod's ρA and ρI shared half-half by the two nodes of each segment of rest
// length l_i, ℓ_i = (l_{i−1} + l_i)/2 per node):
//   m_i = ρ A ℓ_i,   J_i = ρ ℓ_i diag(I, I, 2I),   A = π r², I = π r⁴ / 4,
// and the frames' own force, Euler's gyroscopic torque −ω_i × J_i ω_i (body frame). Elasticity
// is a force field, ChainElasticity. Explicit integrators only (internal DOFs); the point count is
// fixed (refine, coarsen and cut are refused).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Geometry>

#include "filum/core/curve_body.hpp"
#include "filum/core/params.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::mechanics {

class FramedChain final : public CurveBody {
 public:
  /// nodes: n >= 2 positions (m); radius (m) > 0; mass: total (kg) > 0. Frames start with d3
  /// along the chain (at each node, along its first segment; the last node, along its last) by
  /// the shortest turn from e3, so that a straight chain starts untwisted.
  FramedChain(Points nodes, double radius, double mass);

  /// "nodes": {"from": [..], "to": [..], "count": n} (equally spaced) or [[x,y,z], ...];
  /// "radius": m (default 1e-3); "mass": kg or "density": kg/m³;
  /// "angular_velocities": [[ωx,ωy,ωz], ...] one per node, body frame (rad/s; default at rest).
  static std::unique_ptr<FramedChain> fromParams(const Params& p);

  std::string typeName() const override { return "FramedChain"; }

  // Points.
  int pointCount() const override { return static_cast<int>(nodes_.rows()); }
  const Points& initialPositions() const override { return nodes_; }
  void solveMass(PointsRef B) const override;
  void multiplyMass(ConstPointsRef x, PointsRef out) const override;
  void addMassMatrix(double factor, JacobianAccumulator& out) const override;
  int couplingRange() const override { return 1; }
  void addGravity(const Vec3& g, PointsRef B) const override;
  double gravityPotential(const Vec3& g, ConstPointsRef q) const override;

  // Frames: internal DOFs.
  int internalPositionCount() const override { return 4 * pointCount(); }
  int internalVelocityCount() const override { return 3 * pointCount(); }
  void initialInternalState(Eigen::Ref<VecX> q, Eigen::Ref<VecX> v) const override;
  void integrateInternal(Eigen::Ref<const VecX> q0, Eigen::Ref<const VecX> w, Eigen::Ref<VecX> q1) const override;
  void differenceInternal(Eigen::Ref<const VecX> q1, Eigen::Ref<const VecX> q0, Eigen::Ref<VecX> w) const override;
  void addInternalForce(const SceneState& s, Eigen::Ref<VecX> B) const override;
  void solveInternalMass(Eigen::Ref<VecX> B) const override;
  void multiplyInternalMass(Eigen::Ref<const VecX> x, Eigen::Ref<VecX> out) const override;

  // Curve.
  const CurveBasis& basis() const override { return *basis_; }
  double radius() const override { return radius_; }
  double mass() const override { return mass_; }
  SparseMatrix refine(const std::vector<double>& abscissas) override;
  SparseMatrix coarsen(double abscissa, ConstPointsRef q, double tolerance) override;
  SparseMatrix cut(double abscissa) override;

  /// Node i's orientation in the state's q (the internal block), as a unit quaternion.
  Eigen::Quaterniond orientation(const VecX& q, int node) const;
  /// Rest length of segment i (m) and the node's inertia diagonal diag(ρℓI, ρℓI, 2ρℓI) (kg m²).
  double restLength(int segment) const { return rest_lengths_[segment]; }
  const Vec3& nodeInertia(int node) const { return inertia_[node]; }
  double nodeMass(int node) const { return masses_[node]; }

 private:
  Points nodes_;
  double radius_, mass_;
  std::unique_ptr<geometry::SplineBasis> basis_;
  std::vector<double> rest_lengths_, masses_;
  std::vector<Vec3> inertia_;
  std::vector<Eigen::Quaterniond> initial_frames_;
  Points initial_angular_velocities_;  // n × 3 (body frame), empty: at rest
};

}  // namespace filum::mechanics
