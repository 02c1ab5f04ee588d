// PointTarget: what a point constraint holds the curve point P(s) to (paper Fig. 1a, [Lenoir talk 2008]):
//   fixed      X(t) = X0              "target": [x, y, z]   (default: where P(s) starts)
//   scripted   X(t) = path(t)         "path": [{"time": t, "position": [x, y, z]}, ...]
//   attached   X(t) = P2(s2, t) + o = Σ_k b_k(s2) q2_k + o, a point of another spline (or of the
//              same spline at another abscissa), with an optional constant offset o (m) — a hole a
//              needle made in a wound's lip beside the lip's edge curve (haptics/wound.hpp): it
//              translates with the point, its turn neglected; Ẋ and Ẍ are the point's
//              "target": {"object": "node/path", "abscissa": s2, "offset": [x, y, z]}.
//   steered    X(t) = x + u (t − t0), set between steps by an application (steer(): a tool moved
//              by a script or a device, Python's Scene.steer), not by the scene file.
// Fixed and scripted targets are known functions of time whose acceleration Ẍ(t) goes into the
// right-hand side of the rows (0 for fixed targets and linear paths, scripted_path.hpp). An
// attached target moves with its body: its acceleration is an unknown of the same multiplier
// solve, so the rows of the constraint carry −b_k(s2) on the other body's points (the anchor
// spans both bodies) and the multiplier acts on both, with opposite signs (action, reaction).
#pragma once

#include <optional>
#include <string>

#include "filum/geometry/scripted_path.hpp"
#include "filum/core/body_point.hpp"
#include "filum/core/component.hpp"
#include "filum/core/constraint_rows.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/geometry/spline_basis.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum {
class Scene;
}

namespace filum::constraints {

class PointTarget {
 public:
  enum class Kind { kStart, kFixed, kScripted, kAttached, kSteered };

  /// Where the constrained point starts (resolved by init).
  PointTarget() = default;
  static PointTarget fixed(const Vec3& x) { return PointTarget(Kind::kFixed, x); }
  static PointTarget scripted(geometry::ScriptedPath path);
  /// Attached to the point at abscissa s2 ∈ [0, 1] of the spline held by node `object`.
  static PointTarget attached(std::string object, double abscissa);

  /// Reads "target" (array: fixed; object {"object", "abscissa"}: attached) and "path".
  static PointTarget fromParams(const Params& p);

  /// Resolves the default position (start: initial P(s) of the constrained point) and the
  /// attached body; `owner` names the constraint in errors. The own body and abscissa are
  /// passed to refuse an attachment to the very same point (g ≡ 0, a singular system).
  void init(const Scene& scene, const Component& owner, const Vec3& start, const MechanicalState& own_body,
            double own_abscissa);

  /// From time t0 on, X(t) = position + velocity (t − t0) (m, m/s): the target moves at constant
  /// velocity until steered again. Replaces a fixed, start or scripted target (whose path is then
  /// dropped); returns false, changing nothing, for a target attached to a body (it moves with it).
  bool steer(const Vec3& position, const Vec3& velocity, double t0);

  Kind kind() const { return kind_; }
  bool attached() const { return kind_ == Kind::kAttached; }

  /// X(t) at state s (m).
  Vec3 position(const SceneState& s) const;
  /// Ẋ(t) at state s (m/s).
  Vec3 velocity(const SceneState& s) const;
  /// Known part of Ẍ at state s (m/s²): the scripted path's acceleration, else 0.
  Vec3 knownAcceleration(const SceneState& s) const;
  /// Unknown part of Ẍ, Σ_k b_k(s2) A2_k, once the scene accelerations a are solved: 0
  /// unless attached.
  Vec3 attachedAcceleration(const VecX& a) const;
  /// X(t) of a fixed or scripted target (throws std::logic_error if attached).
  Vec3 positionAt(double t) const;

  /// Adds −scale·b_k(s2) on the attached body's points to the current anchor (nothing unless
  /// attached): the target's share of the rows Dᵀ(P(s) − X).
  void addToAnchor(ConstraintRows& rows, double scale = 1.0) const;
  /// Moves an attached target to the abscissa s2 ∈ [0, 1] of its body, offset by o (m): X = P2(s2) + o.
  /// Returns false, changing nothing, for a target that is not attached.
  bool reattach(double abscissa, const Vec3& offset);

  /// Applies the reaction −F at the attached point: B_k −= b_k(s2) F (nothing unless attached).
  void addReaction(const Vec3& F, VecX& B) const;

  /// The attached point (body and abscissa; attached only).
  const BodyPoint& attachedPoint() const { return point_; }
  /// "object" and JSON place of an attached target, for messages.
  const std::string& objectPath() const { return object_; }

 private:
  PointTarget(Kind kind, const Vec3& x) : kind_(kind), position_(x) {}

  Kind kind_ = Kind::kStart;
  Vec3 position_ = Vec3::Zero();  // fixed (and resolved start) position; steered: X(t0)
  Vec3 velocity_ = Vec3::Zero();  // steered: u
  double steered_at_ = 0.0;       // steered: t0
  geometry::ScriptedPath path_;
  std::string object_;     // attached: node path
  std::string where_;      // attached: JSON place of "object" (file: /pointer)
  double abscissa_ = 0.0;  // attached: s2, as read (bound to the body by init)
  Vec3 offset_ = Vec3::Zero();  // attached: o
  BodyPoint point_;        // attached: the point s2 of the target body
};

}  // namespace filum::constraints
