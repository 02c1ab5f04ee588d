// CurveBody: a body whose configuration is a curve P(s) = Σ_i b_i(s) q_i over s ∈ [0, 1]
// (paper eq. 1): the interface through which constraints, collision, haptics and visual see a
// one-dimensional body, whatever its kind (the dynamic spline today; rods with rotations later,
// whose centre line is such a curve). Nothing outside mechanics/ names a concrete body type:
// MechanicalState::curve() gives this interface or null, no cast needed.
//
// Everything a client needs of the curve goes through its basis row at s (BasisRow: the first
// point and the weights b_j(s), b'_j(s), b''_j(s)): the position, tangent and second derivative,
// and the mapping row of a point on the body — a force F at s adds b_j(s) F to point first + j
// (docs/architecture.md, "The three-sided model"). The parameter range is [0, 1]; pointCount()
// is the number of control points, which changes only between steps (Scene::refine, coarsen and
// cut). A cut curve is a sequence of strands (CurveBasis::strands), each a curve of its own
// between its two ends.
#pragma once

#include "filum/core/curve_basis.hpp"
#include "filum/core/mechanical_state.hpp"
#include "filum/core/params.hpp"

#include <string>
#include <vector>

namespace filum {

class CurveBody : public MechanicalState {
 public:
  /// The basis b_i(s) of the curve (its row at s: basis().evaluate(s, row)).
  virtual const CurveBasis& basis() const = 0;
  /// Cross-section radius (m), for collision and skinning: the body's own, or its nominal one
  /// where the section changes along it (radiusVaries: then radiusAt).
  virtual double radius() const = 0;
  /// Whether the cross-section changes along the body (radiusAt differs from radius somewhere).
  virtual bool radiusVaries() const { return false; }
  /// The cross-section radius (m) at abscissa s ∈ [0, 1]: where the section steps from one radius
  /// to another (a node between two spans of a rod), the larger, so that what collides or is drawn
  /// there covers both sides.
  virtual double radiusAt(double /*s*/) const { return radius(); }
  /// A tube's wall: the radius (m) of its lumen at s (0 where the section is solid). Where the
  /// wall steps from one lumen to another, the narrower.
  virtual double innerRadiusAt(double /*s*/) const { return 0.0; }
  /// Whether the body is a tube all along (innerRadiusAt > 0 everywhere).
  virtual bool hollow() const { return false; }
  /// Whether the lumen changes along the body (innerRadiusAt steps somewhere).
  virtual bool innerRadiusVaries() const { return false; }
  /// Where the section is read: every breakpoint and every piece's middle, in non-decreasing order
  /// (repeated where a breakpoint is; radiusAt and innerRadiusAt keep one value between two
  /// breakpoints and may step only at one); just {0} where neither varies.
  std::vector<double> sectionAbscissas() const;
  /// The thinnest and the thickest section's radius (m), read at sectionAbscissas.
  struct RadiusRange {
    double smallest = 0.0;
    double largest = 0.0;
  };
  RadiusRange radiusRange() const;
  /// Total mass (kg).
  virtual double mass() const = 0;

  const CurveBody* curve() const override { return this; }
  CurveBody* curve() override { return this; }

  /// Whether the body carries material frames that take torques (a rod with frames); a spline's
  /// control points take forces only.
  virtual bool takesTorques() const { return false; }
  /// B += the generalized force of a torque τ (N·m, world frame) on the body's material at s
  /// in state st (on the frame that holds s). Only for takesTorques(); others add nothing.
  virtual void addTorque(const SceneState& /*st*/, double /*s*/, const Vec3& /*torque*/, VecX& /*B*/) const {}

  /// Inserts control points without changing the curve (knots at the abscissas s ∈ (0, 1),
  /// exact B-spline knot insertion — the refinement step of adaptive NUBS): the body's model
  /// (basis, rest shape, mass) takes the new points. Returns A (ñ × n) such that the new points
  /// of any configuration are q̃ = A q (and velocities ṽ = A v). Use Scene::refine, which also
  /// lays the scene out anew; called alone it leaves the scene's state on the old layout.
  /// Throws SceneError (at this body) when its basis cannot be refined or an abscissa is not
  /// inside (0, 1).
  virtual SparseMatrix refine(const std::vector<double>& abscissas) = 0;
  /// Removes one control point: the knot at the abscissa s (an interior knot of the body's
  /// B-spline form; geometry/knot_removal.hpp), if the curve moves by at most `tolerance` (m)
  /// there — for the configuration q (this body's points) and for the rest shape alike. Removal
  /// is exact only where the curve is smooth enough (a knot inserted earlier and not yet bent
  /// there comes out exactly); otherwise the points are fitted by least squares and the convex
  /// hull bound says by how much the curve moves. Returns R ((n − 1) × n, q̃ = R q) and updates
  /// the model, or an empty matrix and changes nothing when the bound exceeds the tolerance.
  /// Use Scene::coarsen. Throws SceneError when s is not at a knot of the body.
  virtual SparseMatrix coarsen(double abscissa, ConstPointsRef q, double tolerance) = 0;
  /// Cuts the curve at s ∈ (0, 1) ([Lenoir talk 2008]: "multiple insertion at the same parametric
  /// abscissa decreases the local continuity; local C-1 continuity => cut"): the knot at s raised
  /// to multiplicity degree + 1, so that the body becomes two strands (CurveBasis::strands) that
  /// share no control point, each with its own end at s. The curve is unchanged at that instant;
  /// from then on the strands move apart and no energy, mass or contact chord joins them.
  /// Abscissas keep their meaning (a point at s keeps its place on the thread). Returns A as
  /// refine does (q̃ = A q). Use Scene::cut. Throws SceneError when the body cannot be cut there
  /// (s outside (0, 1), a cut already at s, a basis or body kind that cannot be cut).
  virtual SparseMatrix cut(double abscissa) = 0;

  /// Layout changes a scene file schedules in the body's parameters: "refine": [{"time": t,
  /// "abscissas": [s, ...]}, ...] inserts control points (refine), "cuts": [{"time": t,
  /// "abscissa": s}, ...] cuts the body (cut); times increase within each list. Scene::step
  /// applies each at the first step that starts at or after its time (insertions before cuts
  /// at equal times).
  struct LayoutChange {
    enum class Kind { kRefine, kCut };
    Kind kind = Kind::kRefine;
    double time = 0.0;
    std::vector<double> abscissas;  // refine: the new knots' abscissas; cut: the one abscissa
  };
  /// Reads p["refine"] and p["cuts"] (absent: none), merged by time; throws SceneError at the
  /// faulty entry.
  static std::vector<LayoutChange> layoutChangesFromParams(const Params& p);
  void setLayoutChanges(std::vector<LayoutChange> changes) { layout_changes_ = std::move(changes); }
  /// The first scheduled change not applied yet if it is due at time t, else null.
  const LayoutChange* layoutChangeDue(double t) const {
    return next_layout_change_ < layout_changes_.size() && layout_changes_[next_layout_change_].time <= t
               ? &layout_changes_[next_layout_change_]
               : nullptr;
  }
  void markLayoutChangeApplied() { ++next_layout_change_; }

  /// Counts the layout changes of this body (refine, coarsen, cut): whoever keeps indices into its points
  /// or rows of its basis (mappings, visuals) compares it with the count it was built for.
  long layoutRevision() const { return layout_revision_; }

  /// The mapping row at s ∈ [0, 1] (clamped): weights and first point, local to this body.
  void row(double s, BasisRow& out) const { basis().evaluate(s, out); }
  /// P(s), P'(s) and P''(s) of this body in the scene state `q` (global 3N vector).
  Vec3 position(const VecX& q, double s) const;
  Vec3 tangent(const VecX& q, double s) const;
  Vec3 secondDerivative(const VecX& q, double s) const;

 protected:
  void noteLayoutChange() { ++layout_revision_; }

 private:
  long layout_revision_ = 0;
  std::vector<LayoutChange> layout_changes_;
  std::size_t next_layout_change_ = 0;
};

}  // namespace filum
