// ChannelConstraint (scene type "ChannelConstraint"): a curve body inside a fixed channel — a
// microcatheter's lumen that a coil is pushed through, an introducer sheath — follows the
// channel's centre line until it leaves by the channel's distal opening. The channel is a polyline
// C(ℓ) (arc length ℓ from its proximal point to its tip at ℓ = L_c); each of n material points of
// the body, s_k = k/n (k = 1 … n: the proximal end s = 0 is left to what pushes it, a
// FixedPointConstraint on a path), is held on it while it is inside, by 2 rows across the channel:
//   g_k = [u w]ᵀ (P(s_k) − C(ℓ_k)) = 0,   ℓ_k = argmin_ℓ |P(s_k) − C(ℓ)|,  (t, u, w) orthonormal,
// t the tangent of the segment ℓ_k lies on, with Baumgarte's −2ω ġ − ω² g on the right-hand side
// (the channel does not move: ġ = [u w]ᵀ Ṗ). Along t the body slides freely (no friction: a
// PTFE-lined lumen), so what pushes the proximal end pushes the body through.
//
// Which points are held, found afresh from the state alone (no memory between steps, so
// save/restore and rollback stay exact): walking from s_1 to s_n, each point is projected onto the
// segments near where the one before it projected (within [ℓ_{k−1} − d_k, ℓ_{k−1} + 2 d_k], d_k the
// distance between the two points, for s_1 its distance from s = 0; s_1 onto the whole polyline),
// and the walk stops at the first
// point that projects within d_k of the tip or beyond, or lies farther than `capture` from the
// centre line: it and every point after it are not held. A coil curled up beside the channel's
// shaft is thus never taken back in; a body pulled back into the channel is, point by point.
//
// The tip support. Where a body in the channel (a point held) crosses the tip's plane (the plane
// through C(L_c) across the last segment's tangent t), at the abscissa σ* with
// t·(P(σ*) − C(L_c)) = 0 found by bisection from the last point held, it passes through the tip:
// two more rows on the material point σ* of this state, g = [u w]ᵀ (P(σ*) − C(L_c)). As σ* moves
// (σ̇* = −t·Ṗ / t·P′), ġ_u = u·(Ṗ + P′ σ̇*) = u′·Ṗ with u′ = u − (u·P′ / t·P′) t (likewise w): the
// rows are u′·a(σ*) = −2ω u′·Ṗ − ω² g_u, oblique (P″ σ̇*² and the like left to the
// stabilization); none where the body leaves the tip at 60° or more to its axis. So the body is
// supported at the tip itself, wherever its nodes are: a node is taken in or let go a spacing
// inside, where the body is already on the centre line (within κ d²/8), and not at the tip, where
// a node hovering at the edge was taken in and let go every few steps with its offset, and the
// stabilization's pull on it fed a rod's oscillation (measured: a rod pushed 3 cm out of a
// straight channel and held oscillated by ±0.5 mm at its tip for seconds).
//
// The clearance between the body and the lumen is neglected (the body's centre line on the
// channel's): for a 0.254 mm coil in a 0.42 mm microcatheter lumen the coil's axis could wander by
// 83 µm. What it saves: a contact row per sphere that starts on the lumen's axis, where its normal
// is undefined (docs/vessels.md, "The coil pushed out of a microcatheter").
//
// Scene parameters: "centre_line" (m, at least 2 points, proximal to distal), "samples" (n, default
// and at most the body's point count − 1: more would give rows that depend on each other), "capture" (m, default 4 radii of the body's thickest section), "stabilization"
// (ω, 1/s, default 0.1/dt). The rows' count changes as points leave: rowCount() is that of the
// last buildRows; violation() reports 2n + 2 entries (the tip's last), zero for what is not held.
#pragma once

#include <memory>
#include <vector>

#include "filum/constraints/baumgarte.hpp"
#include "filum/core/body_point.hpp"
#include "filum/core/constraint.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

class ChannelConstraint final : public Constraint {
 public:
  /// path: the channel's centre line (m, ≥ 2 distinct points); samples: n ≥ 1 (0: the body's
  /// point count − 1, at least 1); capture: m (0: 4 radii of the body's thickest section).
  ChannelConstraint(Points path, int samples, double capture, Baumgarte stabilization);
  static std::unique_ptr<ChannelConstraint> fromParams(const Params& p);

  std::string typeName() const override { return "ChannelConstraint"; }
  int rowCount() const override { return rows_built_; }
  void buildRows(const SceneState& s, ConstraintRows& rows) const override;
  int violationCount() const override { return 2 * static_cast<int>(samples_.size()) + 2; }  // + the tip
  void violation(const SceneState& s, VecX& g, int first) const override;
  void actingAbscissas(const SceneState& s, std::vector<double>& out) const override;

  /// How many of the n points are held at state s (the tip support not counted).
  int insideCount(const SceneState& s) const;

 private:
  /// The channel's point nearest to x among the segments that overlap [from, to] (arc lengths, m):
  /// its arc length ℓ, the point C(ℓ) and its segment's unit tangent.
  struct Projection {
    double arc = 0.0;
    Vec3 point = Vec3::Zero();
    Vec3 tangent = Vec3::UnitX();
  };
  Projection project(const Vec3& x, double from, double to) const;
  void init(const Scene& scene) override;
  /// Calls visit(k, P(s_k), projection) for each point held, in order (the walk above); returns
  /// how many were.
  template <class Visit>
  int forEachInside(const SceneState& s, Visit&& visit) const;
  /// σ*, where the body crosses the tip's plane after its first `inside` points (see the header);
  /// false when none is held, when it does not cross it, or crosses it farther than `capture` from
  /// the tip or at 60° or more to its axis.
  bool findTipCrossing(const SceneState& s, int inside, double& abscissa) const;

  Points path_;
  std::vector<double> arc_;  // arc length at each path point: arc_[0] = 0, arc_.back() = L_c
  int requested_samples_;
  double capture_;
  Baumgarte baumgarte_;
  std::vector<BodyPoint> samples_;  // s_k = k/n, k = 1 … n
  mutable int rows_built_ = 0;
};

}  // namespace filum::constraints
