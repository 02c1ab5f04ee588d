// Topology and tightness of a knotted thread for the knot tests: the curve sampled densely, its
// knot determinant once closed far away (collision/knot_determinant.hpp) and the length of
// thread pressed in the knot.
#pragma once

#include <algorithm>
#include <utility>

#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/knot_determinant.hpp"
#include "filum/core/scene.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::test {

/// The curve of body `body` at state s, sampled at `count` equal parametric steps.
inline Points sampledCurve(const Scene& scene, int body, const SceneState& s, int count = 400) {
  const auto& spline = *scene.bodies()[body]->curve();
  return geometry::sampleCurve(spline.basis(), spline.block(s.q), count);
}

/// Knot determinant of an open polyline closed far away (1: unknotted, 3: overhand knot).
inline long openKnotDeterminant(const Points& curve) {
  return collision::knotDeterminant(collision::closeFarAway(curve));
}

/// Abscissa range [lo, hi] of the thread's self-contacts in the current contact set: the part
/// of the thread the knot holds pressed together (lo > hi without self-contact).
inline std::pair<double, double> knotContactRange(const Scene& scene, int body) {
  const auto& pipeline = dynamic_cast<const collision::ContactPipeline&>(*scene.collisionPipeline());
  double lo = 2.0, hi = -1.0;
  for (const collision::Contact& c : pipeline.contacts())
    if (!c.againstObstacle() && c.model_a == c.model_b && pipeline.models()[c.model_a]->bodyIndex() == body) {
      lo = std::min({lo, c.a.abscissa(), c.b.abscissa()});
      hi = std::max({hi, c.a.abscissa(), c.b.abscissa()});
    }
  return {lo, hi};
}

/// Length of thread (m) between abscissas lo and hi at state s.
inline double threadLength(const Scene& scene, int body, const SceneState& s, double lo, double hi) {
  const auto& spline = *scene.bodies()[body]->curve();
  const geometry::ArcLengthParameterization arc(spline.basis(), spline.block(s.q), 1e-8);
  return arc.lengthAt(hi) - arc.lengthAt(lo);
}

/// Diameter (m) of the piece of thread between abscissas lo and hi at state s: the largest
/// distance between two of its points (200 samples).
inline double pieceDiameter(const Scene& scene, int body, const SceneState& s, double lo, double hi) {
  const auto& spline = *scene.bodies()[body]->curve();
  const int n = 200;
  Points x(n, 3);
  for (int k = 0; k < n; ++k)
    x.row(k) = geometry::curvePoint(spline.basis(), spline.block(s.q), lo + (hi - lo) * k / (n - 1)).transpose();
  double d = 0.0;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j) d = std::max(d, (x.row(i) - x.row(j)).norm());
  return d;
}

}  // namespace filum::test
