#include "filum/mechanics/tissue_attachment.hpp"

#include <array>
#include <cmath>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/arc_length.hpp"

namespace filum::mechanics {

namespace {

/// The spring of one point: d = P(s) − a; taut when |d| > r.
struct Spring {
  Vec3 d = Vec3::Zero();
  double length = 0.0;
  bool taut = false;
};

Spring springAt(const Vec3& position, const Vec3& anchor, double rest) {
  Spring spring;
  spring.d = position - anchor;
  spring.length = spring.d.norm();
  spring.taut = spring.length > rest && spring.length > 0.0;
  return spring;
}

}  // namespace

TissueAttachment::TissueAttachment(Settings settings) : settings_(settings) {}

std::unique_ptr<TissueAttachment> TissueAttachment::fromParams(const Params& p) {
  Settings s;
  s.from = p.has("from") ? p.abscissa("from") : 0.0;
  s.to = p.has("to") ? p.abscissa("to") : 1.0;
  if (!(s.to > s.from)) p.fail("to", "an abscissa after 'from' (" + std::to_string(s.from) + ")", std::to_string(s.to));
  s.count = p.integer("count", 1, kMaxCount, 10, "one spring per point; more than a curve can resolve");
  s.stiffness = p.positive({"stiffness", "N/m²"});
  s.damping = p.nonNegative({"damping", "N·s/m²"}, 0.0);
  const std::string anchors = p.string("anchors", p.has("root") ? "root" : "initial");
  if (anchors == "root") {
    if (!p.has("root")) p.fail("root", "a root line {\"from\": [m], \"to\": [m]} for \"anchors\": \"root\"");
    const Params root = p.object("root");
    s.root = true;
    s.root_from = root.vec3({"from", "m"});
    s.root_to = root.vec3({"to", "m"});
    root.finish();
  } else if (anchors != "initial") {
    p.fail("anchors", "\"initial\" (where the points start) or \"root\" (along the root line)", "\"" + anchors + "\"");
  } else if (p.has("root")) {
    p.fail("root", "no root line with \"anchors\": \"initial\"");
  }
  if (p.has("rest_length") && p.raw({"rest_length", "m"}).is_string()) {
    const std::string rest = p.string("rest_length");
    if (rest != "initial") p.fail("rest_length", "a length in metres >= 0 or \"initial\"", "\"" + rest + "\"");
    s.initial_rest_length = true;
  } else {
    s.rest_length = p.nonNegative({"rest_length", "m"}, 0.0);
  }
  return std::make_unique<TissueAttachment>(s);
}

void TissueAttachment::init(const Scene& scene) {
  curve_ = body().curve();
  if (!curve_) throw SceneError(origin(), "a curve body for " + describe(), body().describe());
  // Bound again after every layout change (refine, coarsen, cut: Scene::relayout): the tissue is
  // what it was at the start — its points keep their abscissas, their anchors and rest lengths.
  if (abscissas_.empty()) placePoints(scene.state().q);
  points_.resize(abscissas_.size());
  for (std::size_t i = 0; i < abscissas_.size(); ++i) points_[i].attach(*curve_, abscissas_[i]);
}

void TissueAttachment::placePoints(const VecX& q) {
  // L₀: the curve's arc length at the start (adaptive Gauss–Legendre, geometry/arc_length.hpp).
  const double length = geometry::curveLength(curve_->basis(), body().block(q));
  const int n = settings_.count;
  const double piece = (settings_.to - settings_.from) * length / n;
  point_stiffness_ = settings_.stiffness * piece;
  point_damping_ = settings_.damping * piece;
  abscissas_.resize(n);
  anchors_.resize(n);
  rest_lengths_.resize(n);
  for (int i = 0; i < n; ++i) {
    const double fraction = (i + 0.5) / n;
    abscissas_[i] = settings_.from + fraction * (settings_.to - settings_.from);
    const Vec3 position = curve_->position(q, abscissas_[i]);
    anchors_[i] = settings_.root ? Vec3(settings_.root_from + fraction * (settings_.root_to - settings_.root_from))
                                 : position;
    rest_lengths_[i] = settings_.initial_rest_length ? (position - anchors_[i]).norm() : settings_.rest_length;
  }
}

Vec3 TissueAttachment::springForce(const SceneState& s, int i) const {
  const Spring spring = springAt(curve_->position(s.q, abscissas_[i]), anchors_[i], rest_lengths_[i]);
  if (!spring.taut) return Vec3::Zero();
  return -point_stiffness_ * (1.0 - rest_lengths_[i] / spring.length) * spring.d;
}

double TissueAttachment::totalTension(const SceneState& s) const {
  double sum = 0.0;
  for (int i = 0; i < settings_.count; ++i) sum += springForce(s, i).norm();
  return sum;
}

void TissueAttachment::addForce(const SceneState& s, VecX& B) const {
  for (int i = 0; i < settings_.count; ++i) {
    const BodyPoint& point = points_[i];
    const Spring spring = springAt(point.map(s.q), anchors_[i], rest_lengths_[i]);
    // F = −k_i (1 − r_i/|d|) d − c_i Ṗ(s_i); Q_j = b_j(s_i) F.
    Vec3 force = -point_damping_ * point.map(s.v);
    if (spring.taut) force -= point_stiffness_ * (1.0 - rest_lengths_[i] / spring.length) * spring.d;
    point.addForce(force, B);
  }
}

double TissueAttachment::potentialEnergy(const SceneState& s) const {
  double energy = 0.0;
  for (int i = 0; i < settings_.count; ++i) {
    const Spring spring = springAt(curve_->position(s.q, abscissas_[i]), anchors_[i], rest_lengths_[i]);
    if (spring.taut) energy += 0.5 * point_stiffness_ * (spring.length - rest_lengths_[i]) * (spring.length - rest_lengths_[i]);
  }
  return energy;
}

void TissueAttachment::addJacobian(const SceneState& s, double k_factor, double d_factor,
                                   JacobianAccumulator& out) const {
  std::array<Eigen::Matrix3d, BasisRow::kMaxSupport*(BasisRow::kMaxSupport + 1) / 2> lower;
  for (int i = 0; i < settings_.count; ++i) {
    // Jᵀ (∂F/∂P) J over the point's mapping row b(s_i), as the symmetric support block.
    const BasisRow& row = points_[i].row();
    const int first = points_[i].firstPoint();
    // The 3 × 3 block of one point: k_factor ∂F/∂P + d_factor ∂F/∂Ṗ, then b_j b_m times it.
    Eigen::Matrix3d block = (-d_factor * point_damping_) * Eigen::Matrix3d::Identity();
    if (k_factor != 0.0) {
      const Spring spring = springAt(points_[i].map(s.q), anchors_[i], rest_lengths_[i]);
      if (spring.taut) {
        const double ratio = rest_lengths_[i] / spring.length;
        const Vec3 unit = spring.d / spring.length;
        // ∂F/∂P = −k_i [(1 − r/|d|) I + (r/|d|) d̂ d̂ᵀ]
        block -= k_factor * point_stiffness_ *
                 ((1.0 - ratio) * Eigen::Matrix3d::Identity() + ratio * unit * unit.transpose());
      }
    }
    for (int a = 0, k = 0; a < row.count; ++a)
      for (int b = 0; b <= a; ++b, ++k) lower[k] = (row.value[a] * row.value[b]) * block;
    out.addSupportBlocks(first, row.count, lower.data());
  }
}

}  // namespace filum::mechanics
