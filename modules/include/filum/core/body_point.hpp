// BodyPoint: a material point of a curve body, and the mapping of that one point — the one route
// by which a force at a point of a curve reaches the body's control points (docs/architecture.md,
// "The three-sided model"). Everyone who applies a force at a point of a curve holds one:
// constraints (their own point, an attached target, junctions), contacts (both sides), springs
// (their end points), point loads, tissue attachments and the haptic tool's grasp and push
// samples.
//
// Two kinds of point, one mapping. A point of the curve at abscissa s,
//   x = P(s) = Σ_j b_j(s) q_{first+j}                                  (paper eq. 1),
// and a point of the chord between two points of the curve (a contact between two sphere
// samples, collision/sphere_sampling_mapping.hpp),
//   x = (1 − t) P(s₀) + t P(s₁) = Σ_j w_j q_{p_j},  w = (1 − t) b(s₀) + t b(s₁)  (rows merged).
// Both are linear in q: the mapping's Jacobian is the constant row w ⊗ I₃, so positions and
// velocities go down as x = Σ w_j q_{p_j}, ẋ = Σ w_j q̇_{p_j} (apply, applyJ), and a force F at the
// point goes up as Q_{p_j} += w_j F (applyJT; paper §3: "forces can be applied on any point of
// the spline"), whose virtual work is F·ẋ.
//
// The weights belong to the body's layout when they were evaluated; after the body changes its
// points (CurveBody::refine, coarsen, Scene::refine) every accessor evaluates them again at the
// same abscissas in the new basis, on first use (the body's layoutRevision() tells): a refinement
// keeps the curve, so the point stays where it was, and no holder can use weights of a layout
// that is gone. A point at a strand's end at a cut keeps the strand's own end point (its row
// evaluated from the left, CurveBasis::strands). Global indices read the body's offset live, so a
// point also follows another body's change.
#pragma once

#include <array>
#include <cassert>

#include "filum/core/curve_body.hpp"
#include "filum/core/mapping.hpp"

namespace filum {

/// The mapping row of a point as weights on its body's control points: x = Σ_j weight[j]
/// q_{point[j]}, point[] local to the body, up to two basis rows merged (a chord point).
struct PointWeights {
  static constexpr int kMax = 2 * BasisRow::kMaxSupport;
  int count = 0;
  std::array<int, kMax> point{};      // control point index within the body
  std::array<double, kMax> weight{};  // dimensionless, sum 1

  /// += scale · b(s) over the row's points, merged with the points already held.
  void add(const BasisRow& row, double scale);
};

inline void PointWeights::add(const BasisRow& row, double scale) {
  if (scale == 0.0) return;
  for (int j = 0; j < row.count; ++j) {
    const int p = row.first + j;
    int slot = 0;
    while (slot < count && point[slot] != p) ++slot;
    if (slot == count) {
      point[count] = p;
      weight[count++] = 0.0;
    }
    weight[slot] += scale * row.value[j];
  }
}

class BodyPoint final : public Mapping {
 public:
  BodyPoint() = default;
  BodyPoint(const CurveBody& body, double abscissa) { attach(body, abscissa); }

  std::string typeName() const override { return "BodyPoint"; }

  /// The point at abscissa s ∈ [0, 1] of `body` (its row evaluated now).
  void attach(const CurveBody& body, double abscissa) {
    body_ = &body;
    moveTo(abscissa);
  }
  /// The same, with the row at s already evaluated in the body's current layout (a sphere
  /// sample's row, collision/sphere_sampling_mapping.hpp); from_left: the row is the left limit
  /// at s (a strand's end at a cut: evaluateOnStrand), and is evaluated so again after a change.
  void attach(const CurveBody& body, double abscissa, const BasisRow& row, bool from_left = false) {
    body_ = &body;
    setCurvePoint(abscissa, row, from_left);
  }
  /// The point (1 − t) P(s₀) + t P(s₁) of the chord between two points of `body` (t ∈ [0, 1]),
  /// from their rows in the body's current layout; its abscissa, for reports and for the
  /// holders that track points along the body, is (1 − t) s₀ + t s₁. t = 0 is the curve point s₀.
  /// from_left0/1 as for attach (a chord ends at its strand's last point).
  void attachChord(const CurveBody& body, double s0, const BasisRow& row0, double s1, const BasisRow& row1,
                   double t, bool from_left0 = false, bool from_left1 = false) {
    body_ = &body;
    if (t <= 0.0) return setCurvePoint(s0, row0, from_left0);
    s0_ = s0;
    s1_ = s1;
    t_ = t;
    from_left0_ = from_left0;
    from_left1_ = from_left1;
    abscissa_ = (1.0 - t) * s0 + t * s1;
    mergeChord(row0, row1);
    revision_ = body.layoutRevision();
  }
  /// Another abscissa on the same body (a sliding point, a grasp that moves): a point of the
  /// curve from then on. A detached point only keeps the abscissa.
  void moveTo(double abscissa) {
    t_ = 0.0;
    abscissa_ = abscissa;
    from_left0_ = false;
    if (!body_) return;
    body_->row(abscissa_, row_);
    setCurvePoint(abscissa_, row_, false);
  }
  /// The weights again if the body's layout changed since they were evaluated (no-op otherwise;
  /// the accessors below do it themselves).
  void refresh() const {
    if (!body_ || revision_ == body_->layoutRevision()) return;
    if (t_ == 0.0) {
      evaluate(abscissa_, from_left0_, row_);
      fillFromRow();
    } else {
      BasisRow row1;
      evaluate(s0_, from_left0_, row_);
      evaluate(s1_, from_left1_, row1);
      mergeChord(row_, row1);
    }
    revision_ = body_->layoutRevision();
  }
  void detach() { body_ = nullptr; }

  bool attached() const { return body_ != nullptr; }
  const CurveBody* body() const { return body_; }
  double abscissa() const { return abscissa_; }
  /// Whether the point lies on a chord between two points of the curve (not on the curve).
  bool onChord() const { return t_ != 0.0; }
  /// The mapping row: weights on the body's control points.
  const PointWeights& weights() const {
    refresh();
    return weights_;
  }
  /// The basis row at the abscissa, with its derivatives b'(s), b''(s) — a point of the curve
  /// only (a chord point has no single row; onChord()).
  const BasisRow& row() const {
    assert(!onChord() && "BodyPoint::row() of a chord point");
    refresh();
    return row_;
  }
  /// Global index (scene numbering) of the row's first point (a point of the curve).
  int firstPoint() const { return body_->offset() + row().first; }

  // The mapping of the one point (Mapping): the body's control points (pointCount() × 3) in,
  // the point (1 × 3) out. Linear: J does not depend on `in`.
  int inputCount() const override { return body_->pointCount(); }
  int outputCount() const override { return 1; }
  /// x = Σ_j w_j q_{p_j}.
  void apply(ConstPointsRef in, PointsRef out) const override { out.row(0) = combine(in).transpose(); }
  /// ẋ = Σ_j w_j q̇_{p_j}.
  void applyJ(ConstPointsRef, ConstPointsRef v_in, PointsRef v_out) const override {
    v_out.row(0) = combine(v_in).transpose();
  }
  /// Q_{p_j} += w_j F (accumulates).
  void applyJT(ConstPointsRef, ConstPointsRef f_out, PointsRef f_in) const override { scatter(f_out, f_in); }
  /// w ⊗ I₃: 3 × 3·pointCount().
  SparseMatrix jacobian(ConstPointsRef in) const override;

  // The same on the scene's global 3N vectors.
  /// Σ_j w_j x_{p_j} of a global 3N vector: the point for q, its velocity for v, its
  /// acceleration for accelerations.
  Vec3 map(const VecX& global) const { return combine(body_->block(global)); }
  /// P'(s) (m per unit of s) of a global 3N vector (a point of the curve).
  Vec3 mapTangent(const VecX& global) const {
    const BasisRow& b = row();
    const int first = body_->offset() + b.first;
    Vec3 sum = Vec3::Zero();
    for (int j = 0; j < b.count; ++j) sum += b.d1[j] * global.segment<3>(3 * (first + j));
    return sum;
  }
  /// B += scale · Jᵀ F: a force F (N) at the point, mapped up as applyJT maps it.
  void addForce(const Vec3& F, VecX& B, double scale = 1.0) const {
    const Eigen::Matrix<double, 1, 3, Eigen::RowMajor> f = scale * F.transpose();
    scatter(f, body_->block(B));
  }
  /// visit(global point, w_j) for the mapping row's points (the Jacobian row, to assemble
  /// constraint rows and stiffness blocks).
  template <class Visit>
  void forEachWeight(Visit&& visit) const {
    const PointWeights& w = weights();
    const int offset = body_->offset();
    for (int j = 0; j < w.count; ++j) visit(offset + w.point[j], w.weight[j]);
  }

 private:
  void setCurvePoint(double abscissa, const BasisRow& row, bool from_left) {
    t_ = 0.0;
    abscissa_ = abscissa;
    from_left0_ = from_left;
    if (&row != &row_) row_ = row;
    fillFromRow();
    revision_ = body_->layoutRevision();
  }
  void fillFromRow() const {
    weights_.count = row_.count;
    for (int j = 0; j < row_.count; ++j) {
      weights_.point[j] = row_.first + j;
      weights_.weight[j] = row_.value[j];
    }
  }
  /// b(s) in the body's current layout: its left limit for a strand's end at a cut.
  void evaluate(double s, bool from_left, BasisRow& out) const {
    if (from_left)
      body_->basis().evaluateFromLeft(s, out);
    else
      body_->row(s, out);
  }
  /// out_{p_j} += w_j f (f: 1 × 3): Jᵀ f.
  void scatter(ConstPointsRef f, PointsRef out) const {
    const PointWeights& w = weights();
    for (int j = 0; j < w.count; ++j) out.row(w.point[j]) += w.weight[j] * f.row(0);
  }
  void mergeChord(const BasisRow& row0, const BasisRow& row1) const {
    weights_.count = 0;
    weights_.add(row0, 1.0 - t_);
    weights_.add(row1, t_);
  }
  /// Σ_j w_j x_{p_j} over the body's points x.
  Vec3 combine(ConstPointsRef x) const {
    const PointWeights& w = weights();
    Vec3 sum = Vec3::Zero();
    for (int j = 0; j < w.count; ++j) sum += w.weight[j] * x.row(w.point[j]).transpose();
    return sum;
  }

  const CurveBody* body_ = nullptr;
  double abscissa_ = 0.0;
  double s0_ = 0.0, s1_ = 0.0, t_ = 0.0;  // a chord point: its ends and place (t_ = 0: on the curve)
  bool from_left0_ = false, from_left1_ = false;  // rows at s (s0_) and s1_ are left limits
  mutable BasisRow row_;          // b(s) in the body's layout of revision_ (a point of the curve)
  mutable PointWeights weights_;  // the mapping row in that layout
  mutable long revision_ = -1;
};

}  // namespace filum
