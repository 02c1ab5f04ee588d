// SphereModel (scene type "SphereModel"): spheres to show probes, instruments, constraint
// targets and, for debugging, the collision spheres sampled along a thread. Where they sit:
//   "center": [x, y, z]       one fixed sphere (no body needed);
//   "abscissa": s             one sphere following P(s) of the node's spline (or "object");
//   "abscissas": [s1, ...]    several, following the spline;
//   "count": n                n spheres at equal rest arc length along the spline, s = 0 to 1
//                             (the collision spheres' layout);
//   "constraint": "name"      the target X(t) of a point or sliding-point constraint (a
//                             scripted grip, a fixed point's anchor, a needle hole), hidden
//                             once the constraint is released;
//   "path": [{"time", "position"}, ...]  a scripted path (geometry/scripted_path.hpp, with
//                             "interpolation"), e.g. the same path as a ProbeSphere obstacle.
// "radius" (m; default the spline's radius: on a body whose section changes along it, as a rod's
// spans, each sphere on the curve takes the body's radius at its abscissa), "resolution" (latitude rings, default 12),
// "color", "opacity". Points on the spline go through a SplineAxisMapping (positions down).
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "filum/geometry/scripted_path.hpp"
#include "filum/visual/spline_axis_mapping.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum {
class Constraint;
}

namespace filum::visual {

class SphereModel final : public VisualModel {
 public:
  enum class Placement { kFixed, kOnCurve, kEvenlyOnCurve, kConstraintTarget, kScriptedPath };
  struct Options {
    Placement placement = Placement::kFixed;
    Vec3 center = Vec3::Zero();       // kFixed
    std::vector<double> abscissas;    // kOnCurve
    int count = 0;                    // kEvenlyOnCurve
    std::string constraint;           // kConstraintTarget, by name
    const Constraint* target = nullptr;  // kConstraintTarget set in code (VisualScene's markers): this one
    geometry::ScriptedPath path;   // kScriptedPath
    std::optional<double> radius;     // m
    int resolution = 12;
  };
  explicit SphereModel(Options options);
  static std::unique_ptr<SphereModel> fromParams(const Params& p);

  std::string typeName() const override { return "SphereModel"; }
  bool needsBody() const override {
    return options_.placement == Placement::kOnCurve || options_.placement == Placement::kEvenlyOnCurve;
  }
  void update(const SceneState& s) override;
  const TriangleMesh& mesh(int = 0) const override { return mesh_; }

  /// Centres of the last update.
  const Points& centers() const { return centers_; }
  /// Each sphere's radius (m): one per centre where they differ (spheres on a body whose section
  /// changes along it), else empty and all of radius().
  const VecX& radii() const { return radii_; }
  /// The constraint whose target it marks (kConstraintTarget, after init), else null.
  const Constraint* markedConstraint() const { return constraint_; }
  /// The spheres' radius (m), or the largest of radii().
  double radius() const { return radius_; }

 protected:
  void init(const Scene& scene) override;

 private:
  Options options_;
  double radius_ = 0.0;
  VecX radii_;  // per sphere, where the body's section varies (else empty)
  TriangleMesh unit_;
  std::unique_ptr<SplineAxisMapping> mapping_;
  const Constraint* constraint_ = nullptr;
  Points centers_;
  TriangleMesh mesh_;
};

}  // namespace filum::visual
