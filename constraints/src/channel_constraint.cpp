#include "filum/constraints/channel_constraint.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "filum/constraints/curve_lookup.hpp"
#include "filum/constraints/projected_point_constraint.hpp"
#include "filum/constraints/release_schedule.hpp"
#include "filum/core/scene_error.hpp"

namespace filum::constraints {

namespace {
constexpr int kMaxSamples = 100000;  // rows for 2 × this many points: far beyond any body's points
}  // namespace

ChannelConstraint::ChannelConstraint(Points path, int samples, double capture, Baumgarte stabilization)
    : path_(std::move(path)), requested_samples_(samples), capture_(capture), baumgarte_(stabilization) {
  if (path_.rows() < 2) throw std::invalid_argument("ChannelConstraint: a centre line of at least 2 points");
  arc_.assign(static_cast<std::size_t>(path_.rows()), 0.0);
  for (Eigen::Index i = 1; i < path_.rows(); ++i)
    arc_[i] = arc_[i - 1] + (path_.row(i) - path_.row(i - 1)).norm();
}

std::unique_ptr<ChannelConstraint> ChannelConstraint::fromParams(const Params& p) {
  Points path = p.points({"centre_line", "m"}, 2, kMaxSamples, "one segment per 10 µm of a 1 m channel");
  for (Eigen::Index i = 1; i < path.rows(); ++i)
    if (!((path.row(i) - path.row(i - 1)).norm() > 0.0))
      p.fail("centre_line", "distinct consecutive points (a polyline)", "point " + std::to_string(i) + " repeats point " +
                                                                     std::to_string(i - 1));
  const int samples = p.has("samples") ? p.integer("samples", 1, kMaxSamples, "memory") : 0;
  const double capture = p.has({"capture", "m"}) ? p.positive({"capture", "m"}) : 0.0;
  auto c = std::make_unique<ChannelConstraint>(std::move(path), samples, capture, Baumgarte::fromParams(p));
  readReleaseTime(p, *c);
  return c;
}

void ChannelConstraint::init(const Scene& scene) {
  const CurveBody& curve = requireCurve(body(), *this);
  // More points than the body has spans would give rows that depend on each other (a chain's two
  // transverse DOFs per node): a singular system.
  if (requested_samples_ > std::max(1, curve.pointCount() - 1))
    throw SceneError(origin() + "/samples", "at most the body's point count − 1 (" +
                                                std::to_string(std::max(1, curve.pointCount() - 1)) + ") for " + describe(),
                     std::to_string(requested_samples_));
  const int n = requested_samples_ > 0 ? requested_samples_ : std::max(1, curve.pointCount() - 1);
  samples_.assign(static_cast<std::size_t>(n), BodyPoint());
  for (int k = 1; k <= n; ++k) samples_[k - 1].attach(curve, static_cast<double>(k) / n);
  if (capture_ == 0.0) capture_ = 4.0 * curve.radiusRange().largest;  // the thickest section's (a rod's spans)
  baumgarte_.init(scene);
}

ChannelConstraint::Projection ChannelConstraint::project(const Vec3& x, double from, double to) const {
  // Segments [arc_i, arc_{i+1}] overlapping [from, to]: the first by binary search.
  const auto last = static_cast<Eigen::Index>(arc_.size()) - 1;
  Eigen::Index i = std::upper_bound(arc_.begin(), arc_.end(), from) - arc_.begin() - 1;
  i = std::clamp<Eigen::Index>(i, 0, last - 1);
  Projection best;
  double best_distance = std::numeric_limits<double>::infinity();
  for (; i < last && arc_[i] <= to; ++i) {
    const Vec3 a = path_.row(i).transpose();
    const Vec3 e = path_.row(i + 1).transpose() - a;
    const double length = arc_[i + 1] - arc_[i];
    const double t = std::clamp((x - a).dot(e) / (length * length), 0.0, 1.0);
    const Vec3 c = a + t * e;
    const double distance = (x - c).squaredNorm();
    if (distance < best_distance) {
      best_distance = distance;
      best = {arc_[i] + t * length, c, e / length};
    }
  }
  return best;
}

template <class Visit>
int ChannelConstraint::forEachInside(const SceneState& s, Visit&& visit) const {
  // Held while a spacing d_k or more behind the tip (the tip support holds the body there, see
  // the header); returns how many were.
  const double tip = arc_.back();
  double previous_arc = 0.0;
  Vec3 previous = Vec3::Zero();
  for (std::size_t k = 0; k < samples_.size(); ++k) {
    const Vec3 x = samples_[k].map(s.q);
    // d_k: the distance from the point before (for s_1, from the body's start s = 0).
    const double d = (x - (k == 0 ? samples_[0].body()->position(s.q, 0.0) : previous)).norm();
    const Projection p = k == 0 ? project(x, 0.0, tip) : project(x, previous_arc - d, previous_arc + 2.0 * d);
    if (p.arc >= tip - d || (x - p.point).norm() > capture_) return static_cast<int>(k);  // so is every later one
    visit(k, x, p);
    previous_arc = p.arc;
    previous = x;
  }
  return static_cast<int>(samples_.size());
}

bool ChannelConstraint::findTipCrossing(const SceneState& s, int inside, double& abscissa) const {
  // f(σ) = t·(P(σ) − C(L_c)), t the last segment's tangent: negative inside. From the last point
  // held on, the first sample where f >= 0, then bisection between it and the one before (f is
  // continuous along the body), to a round-off bracket.
  const CurveBody& curve = *samples_.front().body();
  const Eigen::Index last = path_.rows() - 1;
  const Vec3 tip = path_.row(last).transpose();
  const Vec3 t = (path_.row(last) - path_.row(last - 1)).normalized().transpose();
  auto f = [&](double sigma) { return t.dot(curve.position(s.q, sigma) - tip); };
  // Only for a body in the channel (a point held, so never before s_1: s = 0 and the spacing
  // after it are left to what pushes the body, whose rows a support there would nearly repeat),
  // and a loop of a body let go that passes the tip is not caught there.
  if (inside == 0) return false;
  const std::size_t first = static_cast<std::size_t>(inside) - 1;
  double lo = samples_[first].abscissa();
  if (f(lo) >= 0.0) return false;
  double hi = -1.0;
  for (std::size_t k = first + 1; k < samples_.size(); ++k) {
    if (f(samples_[k].abscissa()) >= 0.0) {
      hi = samples_[k].abscissa();
      break;
    }
    lo = samples_[k].abscissa();
  }
  if (hi < 0.0) return false;  // the body ends before the tip
  for (int i = 0; i < 60 && hi - lo > 4 * std::numeric_limits<double>::epsilon(); ++i) {
    const double mid = 0.5 * (lo + hi);
    (f(mid) >= 0.0 ? hi : lo) = mid;
  }
  abscissa = hi;
  if ((curve.position(s.q, hi) - tip).norm() > capture_) return false;
  // Leaving the tip at 60° or more to its axis: no support (the oblique rows divide by t·P′).
  BodyPoint point(curve, hi);
  const Vec3 along = point.mapTangent(s.q);
  return t.dot(along) > 0.5 * along.norm();
}

void ChannelConstraint::buildRows(const SceneState& s, ConstraintRows& rows) const {
  // g = [u w]ᵀ (P − C), ġ = [u w]ᵀ Ṗ (the channel is fixed); rows [u w]ᵀ a_P = [u w]ᵀ (−2ω ġ − ω² g).
  rows_built_ = 0;
  auto hold = [&](const BodyPoint& point, const Vec3& x, const Vec3& c, const Vec3& tangent) {
    const Vec3 rhs = baumgarte_.term(Vec3(x - c), Vec3(point.map(s.v)));
    const auto [u, w] = orthonormalComplement(tangent);
    rows.beginAnchor();
    point.forEachWeight([&](int index, double weight) { rows.addAnchorPoint(index, weight); });
    rows.addAnchoredRow(u, u.dot(rhs));
    rows.addAnchoredRow(w, w.dot(rhs));
    rows_built_ += 2;
  };
  const int inside = forEachInside(s, [&](std::size_t k, const Vec3& x, const Projection& p) {
    hold(samples_[k], x, p.point, p.tangent);
  });
  double crossing = 0.0;
  if (!findTipCrossing(s, inside, crossing)) return;
  // The tip support: g = [u w]ᵀ (P(σ*) − C_tip) with σ*(q) on the tip's plane, t·(P(σ*) − C_tip) = 0,
  // so σ̇* = −t·Ṗ / t·P′ and ġ_u = u·(Ṗ + P′ σ̇*) = u′·Ṗ, u′ = u − (u·P′ / t·P′) t (likewise w): the
  // rows u′·a(σ*) = −2ω u′·Ṗ − ω² g_u (P″ σ̇*² and the like left to the stabilization).
  const BodyPoint point(*samples_.front().body(), crossing);
  const Eigen::Index last = path_.rows() - 1;
  const Vec3 tip = path_.row(last).transpose();
  const Vec3 t = (path_.row(last) - path_.row(last - 1)).normalized().transpose();
  const Vec3 along = point.mapTangent(s.q);  // P′(σ*)
  const auto [u, w] = orthonormalComplement(t);
  const Vec3 gap = point.map(s.q) - tip, velocity = point.map(s.v);
  rows.beginAnchor();
  point.forEachWeight([&](int index, double weight) { rows.addAnchorPoint(index, weight); });
  for (const Vec3& d : {u, w}) {
    const Vec3 oblique = d - (d.dot(along) / t.dot(along)) * t;
    rows.addAnchoredRow(oblique, baumgarte_.term(d.dot(gap), oblique.dot(velocity)));
  }
  rows_built_ += 2;
}

void ChannelConstraint::violation(const SceneState& s, VecX& g, int first) const {
  g.segment(first, violationCount()).setZero();
  auto gap = [&](int slot, const Vec3& x, const Vec3& c, const Vec3& tangent) {
    const auto [u, w] = orthonormalComplement(tangent);
    g[first + 2 * slot] = u.dot(x - c);
    g[first + 2 * slot + 1] = w.dot(x - c);
  };
  const int inside = forEachInside(s, [&](std::size_t k, const Vec3& x, const Projection& p) {
    gap(static_cast<int>(k), x, p.point, p.tangent);
  });
  double crossing = 0.0;
  if (!findTipCrossing(s, inside, crossing)) return;
  const Eigen::Index last = path_.rows() - 1;
  gap(static_cast<int>(samples_.size()), samples_.front().body()->position(s.q, crossing), path_.row(last).transpose(),
      (path_.row(last) - path_.row(last - 1)).normalized().transpose());
}

void ChannelConstraint::actingAbscissas(const SceneState& s, std::vector<double>& out) const {
  if (!active()) return;
  const int inside = forEachInside(s, [&](std::size_t k, const Vec3&, const Projection&) { out.push_back(samples_[k].abscissa()); });
  double crossing = 0.0;
  if (findTipCrossing(s, inside, crossing)) out.push_back(crossing);
}

int ChannelConstraint::insideCount(const SceneState& s) const {
  return forEachInside(s, [](std::size_t, const Vec3&, const Projection&) {});
}

}  // namespace filum::constraints
