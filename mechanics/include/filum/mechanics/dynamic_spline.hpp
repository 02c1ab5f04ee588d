// DynamicSpline: the dynamic Lagrangian spline of the paper (§3, after Rémion et al.). Its
// degrees of freedom are the control points q_i(t) of P(s, t) = Σ b_i(s) q_i(t) (eq. 1); the
// Lagrange equations (eq. 2) give M A = B (eq. 3) with the constant banded mass matrix
// M_ij = m ∫ b_i b_j ds, factored once here so that each step's solve is O(n).
//
// Model data only: the control point values live in the scene's SceneState.
#pragma once

#include <memory>

#include "filum/core/curve_body.hpp"
#include "filum/core/params.hpp"
#include "filum/geometry/bspline_curve.hpp"
#include "filum/geometry/spline_basis.hpp"
#include "filum/mechanics/banded_cholesky.hpp"
#include "filum/mechanics/scalar_band.hpp"

namespace filum::mechanics {

/// Control points of one body, at most: a body's state, banded matrices and per-step work grow
/// linearly with the count, and 1e5 is 600 times the largest reference body (rope.json, 165) while a
/// step of it still fits in memory many times over. Checked before anything is allocated.
inline constexpr int kMaxControlPoints = 100000;
/// Coordinates of control points, at most this far from the origin (m): scenes are in metres,
/// and beyond 1e6 m squared distances and energies (stiffness × length²) approach overflow.
inline constexpr double kMaxCoordinate = 1e6;
/// Initial velocity components, at most (m/s): far beyond any motion in surgery, and kinetic
/// energies ½ m v² stay far from overflow.
inline constexpr double kMaxSpeed = 1e6;

class DynamicSpline final : public CurveBody {
 public:
  /// initial: n × 3 control points (m); mass: total mass (kg) > 0; radius: cross-section
  /// radius (m) > 0, used by collision and skinning.
  DynamicSpline(std::unique_ptr<CurveBasis> basis, Points initial, double mass, double radius);

  /// From scene parameters:
  ///   "basis": "uniform_cubic_bspline" (default, C2), "catmull_rom" (C1, interpolating) or "nubs"
  ///      with "degree" 2..5 (default 3) and "knots" (n + degree + 1 values; default clamped
  ///      uniform knots, or uniform with "clamped": false),
  ///   "control_points": [[x,y,z], ...]  or  {"from": [..], "to": [..], "count": n} — a straight
  ///      thread whose curve runs from `from` to `to`,
  ///   "mass": kg  or  "density": kg/m³ (with the radius and the initial arc length),
  ///   "radius": m (default 1e-4, a 3-0 suture is 1e-4 m),
  ///   "velocities": [[vx,vy,vz], ...] one per control point (m/s), the velocities at t = 0
  ///      (default: at rest),
  ///   "refine": [{"time": s, "abscissas": [...]}, ...] control points to insert during the run
  ///      (CurveBody::refine, the curve unchanged; a uniform cubic B-spline becomes a NUBS),
  ///   "cuts": [{"time": s, "abscissa": s}, ...] cuts during the run (CurveBody::cut: the thread
  ///      parts in two strands there).
  static std::unique_ptr<DynamicSpline> fromParams(const Params& p);

  std::string typeName() const override { return "DynamicSpline"; }
  int pointCount() const override { return static_cast<int>(initial_.rows()); }
  const Points& initialPositions() const override { return initial_; }
  void initialVelocities(PointsRef v) const override;
  /// Velocities at t = 0 (n × 3, m/s); zero unless set.
  void setInitialVelocities(Points velocities);
  void solveMass(PointsRef B) const override { factor_.solve(B); }
  void multiplyMass(ConstPointsRef x, PointsRef out) const override { mass_band_.multiply(x, out); }
  /// factor·(M ⊗ I₃) from the sparse M: 2d + 1 isotropic entries per control point.
  void addMassMatrix(double factor, JacobianAccumulator& out) const override;
  int couplingRange() const override { return basis_->degree(); }
  void addGravity(const Vec3& g, PointsRef B) const override;
  double gravityPotential(const Vec3& g, ConstPointsRef q) const override;

  // CurveBody
  const CurveBasis& basis() const override { return *basis_; }
  double mass() const override { return mass_; }
  double radius() const override { return radius_; }
  /// Knot insertion (Oslo, geometry/knot_insertion.hpp) on the curve's knot form: a uniform
  /// cubic B-spline becomes the NUBS on its uniform knots plus the new ones (the same curve and
  /// abscissas); the mass matrix is assembled and factored again (M_ij = m ∫ b_i b_j ds, the
  /// same mass per unit of s, so the same distribution of mass along the thread).
  SparseMatrix refine(const std::vector<double>& abscissas) override;
  /// Knot removal (geometry::removeKnot, least squares on the d − 1 points around the knot) of
  /// the knot at s; R is linear in the points, built column by column from removeKnot.
  SparseMatrix coarsen(double abscissa, ConstPointsRef q, double tolerance) override;
  /// The knot at s raised to multiplicity d + 1 (geometry::splitCurve's refinement): two
  /// strands, each with its own end point at the cut; the mass matrix has no entry across it.
  SparseMatrix cut(double abscissa) override;

  /// Arc length of the initial curve (m).
  double restLength() const { return rest_length_; }
  const SparseMatrix& massMatrix() const { return mass_matrix_; }

 private:
  /// The curve's B-spline form at rest (throws SceneError for a basis without one).
  geometry::BSplineCurve knotForm() const;
  /// Takes the basis on `knots` and the rest shape R · initial, rebuilds the mass matrix.
  void adopt(int degree, std::vector<double> knots, const SparseMatrix& R);

  std::unique_ptr<CurveBasis> basis_;
  Points initial_;            // control points at t = 0 (n × 3, m)
  Points initial_velocities_;  // their velocities at t = 0 (n × 3, m/s; empty: at rest)
  double mass_;               // total mass m (kg)
  double radius_;             // cross-section radius (m)
  double rest_length_;        // arc length of the initial curve (m)
  SparseMatrix mass_matrix_;  // M (n × n)
  ScalarBand mass_band_;      // M as a band (half bandwidth: the degree), for products
  BandedCholesky factor_;     // M = L Lᵀ, computed once
  VecX basis_integrals_;      // w_i = ∫ b_i ds (n)
};

/// Arc length ∫_0^1 |P'(s)| ds by Gauss-Legendre on each polynomial piece.
double arcLength(const CurveBasis& basis, ConstPointsRef q, int nodes_per_piece = 8);

/// A body's total mass (kg) from "mass", or from "density" (kg/m³) as ρ π r² L for its radius
/// and length (m); exactly one of them; SceneError at the faulty key.
double massFromParams(const Params& p, double radius, double length);

/// A basis by name for n control points; throws SceneError at p.where(key) if unknown or n
/// is too small for it.
std::unique_ptr<CurveBasis> makeBasis(const Params& p, const std::string& key, int control_points);

}  // namespace filum::mechanics
