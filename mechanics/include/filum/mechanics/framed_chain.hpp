// FramedChain: a discrete Cosserat rod — a chain of point masses with a material frame on each
// segment between them (Gazzola et al., "Forward and inverse problems in the mechanics of soft
// filaments", R. Soc. open sci. 2018; Spillmann & Teschner's CoRdE keeps frames the same way),
// the second body kind of the kernel and the body of catheters and guidewires. Node i has a
// position x_i (m); segment i (nodes i, i + 1) has an orientation R_i, the rotation from its
// material frame (d1, d2, d3 = R_i e3, d3 along the segment) to the world: a unit quaternion
// (w, x, y, z) in q and the body-frame angular velocity ω_i in v (internal DOFs: 4 positions and
// 3 velocities per segment, MechanicalState). Frames move by R ← R exp(h ω) (a right, body-frame
// increment).
//
// Why frames on segments and not on nodes: a segment's frame follows its own edge (the shear term
// d3_i − t_i, ChainElasticity), and bending lives at the nodes between two segments' frames. With
// a frame per node held to the tangents of both segments around it, a turn θ of the tangent at a
// node was paid as shear, ≈ κGA l θ²/8, beside the bending ½ EI θ²/l: an effective bending
// stiffness EI (1 + κ (G/E) l²/r²), 31 times too stiff at l = 10 mm, r = 1 mm (measured on the
// self-weight elastica before this layout; docs/rods.md).
//
// Its centre line is the polyline through the nodes, P(s) = Σ b_i(s) x_i with the degree-1
// B-spline basis on knots at the nodes' rest arc lengths (s ∈ [0, 1]): a CurveBody, so
// constraints, contacts, tools and skins act on it through their existing code.
//
// Mass, lumped: the rod's ρA shared half-half by the two nodes of each segment of rest length
// l_i (m_i = ρ A ℓ_i, ℓ_i = (l_{i−1} + l_i)/2), and each segment's frame carries the rotary
// inertia of its own slice, J_i = ρ l_i diag(I, I, 2I), with Euler's gyroscopic torque
// −ω_i × J_i ω_i (body frame). The section is a disc of radius r, or a tube's wall (a catheter:
// a lumen of radius r_in < r): A = π (r² − r_in²), I = π (r⁴ − r_in⁴) / 4 (r_in = 0: a disc).
// Elasticity is a force field, ChainElasticity.
// Explicit and implicit integrators: implicit steps put the frames' rotations in the step matrix
// beside the points, interleaved (x0, R0, x1, R1, ...: a band two slots wide), and move frames
// by R ← R exp(w) for the step's increment w. The point count is fixed (refine, coarsen and cut
// are refused).
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
  /// along their segments: the first by the shortest turn from e3, each next one parallel
  /// transported from the one before (the shortest turn from the segment's tangent to the
  /// next's), so that the chain starts untwisted whatever its shape.
  FramedChain(Points nodes, double radius, double mass);
  /// A rod whose cross-section changes along it: each segment's radius (m) and density (kg/m³)
  /// (a stiff shaft and a soft, thin tip); `radius` is the body's nominal radius, and collision
  /// and skins take each segment's own (radiusAt).
  struct Section {
    double radius;
    double density;
    double inner_radius = 0.0;  // m, the lumen of a tube (0: a solid disc), below radius
    /// A = π (r² − r_in²) (m²).
    double area() const;
    /// I = π (r⁴ − r_in⁴) / 4 (m⁴), about a diameter; the polar moment is 2I.
    double secondMoment() const;
  };
  FramedChain(Points nodes, double radius, std::vector<Section> sections);

  /// "nodes": {"from": [..], "to": [..], "count": n} (equally spaced) or [[x,y,z], ...];
  /// "radius": m (default 1e-3); "inner_radius": m, in [0, radius) (default 0: a solid section;
  /// a tube's lumen); "mass": kg or "density": kg/m³;
  /// "angular_velocities": [[ωx,ωy,ωz], ...] one per segment (n − 1), body frame (rad/s;
  /// default at rest); "spans": [{"from": s0, "to": s1, "radius": m, "inner_radius": m,
  /// "density": kg/m³}, ...] (with "density", not "mass"): the cross-section of the segments whose
  /// middle lies in [s0, s1] (later spans win), the rest keeps "radius", "inner_radius" and
  /// "density"; a span's fields default to the body's.
  static std::unique_ptr<FramedChain> fromParams(const Params& p);

  std::string typeName() const override { return "FramedChain"; }

  // Points.
  int pointCount() const override { return static_cast<int>(nodes_.rows()); }
  const Points& initialPositions() const override { return nodes_; }
  void solveMass(PointsRef B) const override;
  void multiplyMass(ConstPointsRef x, PointsRef out) const override;
  void addMassMatrix(double factor, JacobianAccumulator& out) const override;
  /// In step-matrix slots (x0, R0, x1, R1, ...): a segment couples x_i, R_i, x_{i+1} and a node
  /// R_{j−1}, R_j — two slots apart at most.
  int couplingRange() const override { return 2; }
  int stepSlotOfPoint(int i) const override { return 2 * i; }
  int stepSlotOfInternal(int k) const override { return 2 * k + 1; }
  void addGravity(const Vec3& g, PointsRef B) const override;
  double gravityPotential(const Vec3& g, ConstPointsRef q) const override;

  // Frames: internal DOFs.
  int internalPositionCount() const override { return 4 * segmentCount(); }
  int internalVelocityCount() const override { return 3 * segmentCount(); }
  void initialInternalState(Eigen::Ref<VecX> q, Eigen::Ref<VecX> v) const override;
  void integrateInternal(Eigen::Ref<const VecX> q0, Eigen::Ref<const VecX> w, Eigen::Ref<VecX> q1) const override;
  void differenceInternal(Eigen::Ref<const VecX> q1, Eigen::Ref<const VecX> q0, Eigen::Ref<VecX> w) const override;
  void addInternalForce(const SceneState& s, Eigen::Ref<VecX> B) const override;
  void solveInternalMass(Eigen::Ref<VecX> B) const override;
  void multiplyInternalMass(Eigen::Ref<const VecX> x, Eigen::Ref<VecX> out) const override;
  bool supportsImplicitInternal() const override { return true; }
  /// factor · diag(J_i) at each frame's group.
  void addInternalMassMatrix(double factor, JacobianAccumulator& out) const override;

  // Curve.
  const CurveBasis& basis() const override { return *basis_; }
  double radius() const override { return radius_; }
  bool radiusVaries() const override { return radius_varies_; }
  /// The radius of the segment holding s; at a node between two segments (within a few ulps),
  /// the larger of theirs.
  double radiusAt(double s) const override;
  /// The lumen of the segment holding s; at a node between two segments (within a few ulps), the
  /// narrower of theirs.
  double innerRadiusAt(double s) const override;
  bool hollow() const override { return hollow_; }
  bool innerRadiusVaries() const override { return inner_radius_varies_; }
  double mass() const override { return mass_; }
  bool takesTorques() const override { return true; }
  /// On the frame of the segment holding s (body frame: Q_ω += Rᵀ τ).
  void addTorque(const SceneState& st, double s, const Vec3& torque, VecX& B) const override;
  /// The segment holding s ∈ [0, 1] (the last one at s = 1).
  int segmentAt(double s) const;
  SparseMatrix refine(const std::vector<double>& abscissas) override;
  SparseMatrix coarsen(double abscissa, ConstPointsRef q, double tolerance) override;
  SparseMatrix cut(double abscissa) override;

  /// Segments (n − 1), each with a frame.
  int segmentCount() const { return pointCount() - 1; }
  /// Segment i's orientation in the state's q (the internal block), as a unit quaternion.
  Eigen::Quaterniond orientation(const VecX& q, int segment) const;
  /// Rest length of segment i (m); the segment's inertia diagonal diag(ρlI, ρlI, 2ρlI) (kg m²).
  double restLength(int segment) const { return rest_lengths_[segment]; }
  const Vec3& segmentInertia(int segment) const { return inertia_[segment]; }
  /// Segment i's frame in the initial state (parallel transported along the initial nodes).
  const Eigen::Quaterniond& initialFrame(int segment) const { return initial_frames_[segment]; }
  double nodeMass(int node) const { return masses_[node]; }
  /// Segment i's cross-section: radius, density, lumen (area(), secondMoment()).
  const Section& segmentSection(int segment) const { return sections_[segment]; }
  /// Node i's abscissa s ∈ [0, 1] (its rest arc length over the rod's).
  double nodeAbscissa(int node) const { return node_abscissas_[node]; }

 private:
  /// A field of the section of the segment holding s; at a node between two segments (within a few
  /// ulps), the larger (or with !larger the smaller) of theirs.
  double sectionField(double s, double Section::*field, bool larger) const;

  Points nodes_;
  double radius_, mass_;
  std::unique_ptr<CurveBasis> basis_;
  std::vector<double> rest_lengths_, masses_, node_abscissas_;
  std::vector<Section> sections_;  // per segment
  bool radius_varies_ = false;     // some segment's radius is not radius_
  bool hollow_ = false;               // every segment has a lumen
  bool inner_radius_varies_ = false;  // the segments' lumens differ
  std::vector<Vec3> inertia_;                  // per segment
  std::vector<Eigen::Quaterniond> initial_frames_;  // per segment
  Points initial_angular_velocities_;  // (n − 1) × 3 (body frame), empty: at rest
};

}  // namespace filum::mechanics
