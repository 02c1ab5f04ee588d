// BodyPoint: a material point of a curve body — the body and an abscissa s on it, with the basis
// row at s kept: P(s) = Σ_j b_j(s) q_{first + j} (CurveBody). The one form in which a point on a
// body is named by those who hold one: constraints (their own point, an attached target,
// junctions), the haptic tool's grasp and attachments. A force F at the point maps up as
// B_{first+j} += b_j(s) F (docs/architecture.md, "The three-sided model").
//
// The row belongs to the body's layout when it was evaluated; after the body changes its points
// (CurveBody::refine, coarsen, Scene::refine) every accessor evaluates it again at the same s in
// the new basis, on first use (the body's layoutRevision() tells): a refinement keeps the curve,
// so the point stays where it was, and no holder can use a row of a layout that is gone. The
// global index reads the body's offset live, so a point also follows another body's change.
// Contacts are not BodyPoints: a contact point lies between two sphere samples and carries the
// interpolated weights of both (collision/contact.hpp), its abscissa kept for reports.
#pragma once

#include "filum/core/curve_body.hpp"

namespace filum {

class BodyPoint {
 public:
  BodyPoint() = default;
  BodyPoint(const CurveBody& body, double abscissa) { attach(body, abscissa); }

  /// The point at abscissa s ∈ [0, 1] of `body` (the row evaluated now).
  void attach(const CurveBody& body, double abscissa) {
    body_ = &body;
    moveTo(abscissa);
  }
  /// Another abscissa on the same body (a sliding point, a grasp that moves); a detached point
  /// only keeps the abscissa.
  void moveTo(double abscissa) {
    abscissa_ = abscissa;
    if (!body_) return;
    body_->row(abscissa_, row_);
    revision_ = body_->layoutRevision();
  }
  /// The row again if the body's layout changed since it was evaluated (no-op otherwise; the
  /// accessors below do it themselves).
  void refresh() const {
    if (body_ && revision_ != body_->layoutRevision()) {
      body_->row(abscissa_, row_);
      revision_ = body_->layoutRevision();
    }
  }
  void detach() { body_ = nullptr; }

  bool attached() const { return body_ != nullptr; }
  const CurveBody* body() const { return body_; }
  double abscissa() const { return abscissa_; }
  const BasisRow& row() const {
    refresh();
    return row_;
  }
  /// Global index (scene numbering) of the row's first point.
  int firstPoint() const { return body_->offset() + row().first; }

  /// Σ_j b_j x_{first+j} of a global 3N vector: P(s) for q, Ṗ(s) for v, P̈(s) for accelerations.
  Vec3 map(const VecX& global) const { return combine(row().value, global); }
  /// P'(s) (m per unit of s) of a global 3N vector.
  Vec3 mapTangent(const VecX& global) const { return combine(row().d1, global); }
  /// B_{first+j} += scale · b_j F: a force at the point, mapped up.
  void addForce(const Vec3& F, VecX& B, double scale = 1.0) const {
    const BasisRow& b = row();
    const int first = body_->offset() + b.first;
    for (int j = 0; j < b.count; ++j) B.segment<3>(3 * (first + j)) += (scale * b.value[j]) * F;
  }
  /// visit(global point, b_j) for the row's points: the point's mapping row.
  template <class Visit>
  void forEachWeight(Visit&& visit) const {
    const BasisRow& b = row();
    const int first = body_->offset() + b.first;
    for (int j = 0; j < b.count; ++j) visit(first + j, b.value[j]);
  }

 private:
  /// Σ_j w_j x_{first+j} over the row's points, for the row's weights w (values or b').
  Vec3 combine(const std::array<double, BasisRow::kMaxSupport>& weights, const VecX& global) const {
    const int first = firstPoint(), count = row_.count;  // firstPoint() refreshed the row
    Vec3 sum = Vec3::Zero();
    for (int j = 0; j < count; ++j) sum += weights[j] * global.segment<3>(3 * (first + j));
    return sum;
  }

  const CurveBody* body_ = nullptr;
  double abscissa_ = 0.0;
  mutable BasisRow row_;     // b(s) in the body's layout of revision_
  mutable long revision_ = -1;
};

}  // namespace filum
