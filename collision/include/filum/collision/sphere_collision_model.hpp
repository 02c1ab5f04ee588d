// SphereCollisionModel: the collision side of a thread (paper §3: "approximating all objects by
// spheres ... in the case of the thread, spheres are created by a sampling along the curve
// spline"). Spheres of radius r are placed along the DynamicSpline of the component's node at
// curvilinear spacing <= h by a SphereSamplingMapping, resampled at every step as the thread
// stretches ([Lenoir talk 2008]). Between two consecutive centres the union of the spheres is taken as the
// capsule around their chord: thread–thread contacts are computed between chords (segment
// closest points, continuous detection between moving segments), thread–obstacle contacts per
// sphere.
//
// Self-collision skips pairs closer than `exclusion` along the curve: two points of a curve bent
// with radius of curvature ρ at arc distance Δ are 2ρ sin(Δ/2ρ) apart, so with ρ >= r (a thread
// cannot bend tighter than its own radius) points closer than πr along the curve may be within
// 2r of each other without touching; the default exclusion 4r leaves a margin. Where the section
// changes along the body, r is the thicker of the two chords' (a thin tip's own self-contacts
// are sought as near as its radius allows).
//
// A body whose cross-section changes along it (a rod's spans: a thick shaft, a thin tip;
// CurveBody::radiusVaries) gives each sphere the radius at its abscissa (CurveBody::radiusAt,
// the larger one at a node where two spans meet), and the radius along the chord between two
// centres is interpolated linearly (chordRadius). Thread–thread contacts are taken at the centre
// lines' closest points with the radii there, as for a capsule: exact where the radii are equal,
// an approximation on the one chord that holds a step. There the surface is not a true cone
// frustum (with |r_k − r_{k+1}| >= the chord's length the node's sphere holds its neighbour), and
// what an obstacle meets (the spheres) and what another thread meets (the interpolated chord) may
// differ by up to the step |r_k − r_{k+1}|.
//
// Coaxial instruments (a guidewire in a catheter, a coil in a microcatheter): a tube declares the
// radius of its lumen ("lumen_radius", R_in; a body whose section is a tube's wall all along, a
// FramedChain with an "inner_radius", has its wall's lumen without it, spans included, and a
// lumen given must stay within the wall's), and an instrument running in it names the tube's
// node ("inside"). The pipeline then holds the instrument's spheres inside the lumen wherever
// they lie along the tube (narrow_phase.hpp, findLumenContacts) and drops the ordinary contacts
// between the two, which would push them apart.
#pragma once

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <memory>

#include "filum/collision/sphere_sampling_mapping.hpp"
#include "filum/core/collision_pipeline.hpp"
#include "filum/core/params.hpp"
#include "filum/core/scene_state.hpp"

namespace filum {
class Scene;
class CurveBody;
}  // namespace filum

namespace filum::collision {

class SphereCollisionModel final : public CollisionModel {
 public:
  struct Settings {
    double radius = 0.0;        // r (m); 0: the spline's own radius
    double spacing = 0.0;       // h (m); 0: r
    bool self_collision = true;
    double exclusion = -1.0;    // m along the curve; < 0: 4 r
    double lumen_radius = 0.0;  // R_in (m) of a tube's lumen; 0: a solid body
    /// A lumen of another radius over [from, to] of the tube's abscissa (a narrower distal lumen).
    struct LumenSpan {
      double from = 0.0, to = 1.0, radius = 0.0;
    };
    std::vector<LumenSpan> lumen_spans;  // not overlapping; outside them lumen_radius
    std::optional<double> lumen_friction;  // μ inside the lumen; none: the pipeline's
    std::string inside;         // node path of the tube this instrument runs in; empty: none
  };
  explicit SphereCollisionModel(Settings settings) : settings_(settings) {}

  /// "radius": r (m, default: the DynamicSpline's radius), "spacing": h (m, default r),
  /// "self_collision": bool (default true), "exclusion": m along the curve (default 4 r);
  /// a tube: "lumen_radius": R_in (m, below the radius r; default the wall's lumen on a hollow
  /// body, CurveBody::innerRadiusAt), "lumen_spans": [{"from", "to",
  /// "lumen_radius"}] (abscissa ranges of another lumen radius, not overlapping), "lumen_friction":
  /// μ (default the pipeline's "friction"); an instrument in a tube: "inside": the tube's node path.
  static std::unique_ptr<SphereCollisionModel> fromParams(const Params& p);

  std::string typeName() const override { return "SphereCollisionModel"; }

  /// Binds the DynamicSpline of the owner node (SceneError if there is none).
  void init(const Scene& scene);
  /// Resamples the spheres on the curve at state s and maps centres and velocities down.
  void update(const SceneState& s);

  const CurveBody& curve() const { return *curve_; }
  /// Index of the body in Scene::bodies() and of its first point in the state.
  int bodyIndex() const { return body_index_; }
  int pointOffset() const { return point_offset_; }
  /// The largest sphere's radius (m): the body's radius, unless its section changes along it.
  double radius() const { return radius_; }
  /// The thinnest section's radius (m): the body's radius read between and at its breakpoints.
  double smallestRadius() const { return smallest_radius_; }
  /// Sphere k's radius (m), as of the last update.
  double radius(int k) const { return varies_ ? sphere_radii_[k] : radius_; }
  /// The radius (m) of chord k's capsule at t ∈ [0, 1] from centre k to centre k + 1.
  double chordRadius(int k, double t) const {
    return varies_ ? (1.0 - t) * sphere_radii_[k] + t * sphere_radii_[k + 1] : radius_;
  }
  /// The larger of chord k's two radii.
  double chordRadius(int k) const { return varies_ ? std::max(sphere_radii_[k], sphere_radii_[k + 1]) : radius_; }
  /// The arc length (m) along the curve within which two points of chords k and l do not
  /// collide: the "exclusion" given, else 4 r of the thicker of the two chords (header).
  double exclusion(int k, int l) const {
    return varies_ && settings_.exclusion < 0.0 ? 4.0 * std::max(chordRadius(k), chordRadius(l)) : exclusion_;
  }
  bool selfCollision() const { return settings_.self_collision; }
  /// R_in (m) of the lumen of a tube, its widest section where it changes along the tube
  /// ("lumen_spans"); 0 for a solid body.
  double lumenRadius() const { return widest_lumen_; }
  /// The narrowest section of the lumen (m); 0 for a solid body.
  double narrowestLumen() const { return narrowest_lumen_; }
  /// R_in(s) at abscissa s: the span's holding s, else "lumen_radius"; at the end of a span, the
  /// smaller of the two sides within [0, 1] (the narrower wall holds there).
  double lumenRadiusAt(double s) const;
  /// R_in at sphere k, as of the last update.
  double lumenRadius(int k) const { return lumen_varies_ ? sphere_lumens_[k] : settings_.lumen_radius; }
  /// R_in along chord k at t ∈ [0, 1] from centre k to centre k + 1 (linear between the spheres').
  double lumenRadius(int k, double t) const {
    return lumen_varies_ ? (1.0 - t) * sphere_lumens_[k] + t * sphere_lumens_[k + 1] : settings_.lumen_radius;
  }
  const std::optional<double>& lumenFriction() const { return settings_.lumen_friction; }
  /// The node path of the tube this instrument runs in, or empty.
  const std::string& inside() const { return settings_.inside; }

  const SphereSamplingMapping& mapping() const { return *mapping_; }
  int sphereCount() const { return mapping_->outputCount(); }
  /// Centres x_k (m) and their velocities (m/s) at the state of the last update, K × 3.
  const Points& centers() const { return centers_; }
  const Points& velocities() const { return velocities_; }

 private:
  /// sphere_radii_ and sphere_lumens_ from the body's section and the lumen's at the spheres'
  /// abscissas (while they vary).
  void updateRadii();
  /// Abscissas at which R_in and r take every value they take along the body (both are constant
  /// between the body's breakpoints and the lumen spans' ends).
  std::vector<double> sectionSamples() const;
  /// SceneError unless R_in(s) < r(s) all along the tube.
  void checkLumen() const;
  /// lumen_radius and lumen_spans from the body's wall (CurveBody::innerRadiusAt), for a hollow
  /// body that was given no lumen.
  void lumenFromWall();
  /// SceneError where the lumen is wider than the body's wall's lumen (where it has one).
  void checkLumenInsideWall() const;

  Settings settings_;
  const CurveBody* curve_ = nullptr;
  int body_index_ = 0;
  int point_offset_ = 0;
  double radius_ = 0.0;
  double smallest_radius_ = 0.0;
  bool varies_ = false;               // the spheres' radii follow the body's section (radiusAt)
  std::vector<double> sphere_radii_;  // per sphere while varies_ (capacity as centers_)
  bool lumen_varies_ = false;         // "lumen_spans" given
  bool lumen_from_wall_ = false;      // settings_'s lumen read from the body's wall (lumenFromWall)
  double widest_lumen_ = 0.0, narrowest_lumen_ = 0.0;
  std::vector<double> sphere_lumens_;  // R_in per sphere while lumen_varies_ (capacity as centers_)
  double exclusion_ = 0.0;
  std::unique_ptr<SphereSamplingMapping> mapping_;
  Points centers_, velocities_;
};

}  // namespace filum::collision
