// A point's offset from a rod's centre line — the polyline through its points, as the lumen
// contact's chords take it (coaxial instruments: a wire held in a catheter's lumen), found by
// every chord's closest point in closed form, apart from the contact pipeline's own search.
#pragma once

#include <algorithm>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene_state.hpp"
#include "filum/core/types.hpp"

namespace filum::test {

/// x minus the nearest point of the tube's centre line (polyline through its points) in state s.
inline Vec3 offsetFromAxis(const CurveBody& tube, const SceneState& s, const Vec3& x) {
  const auto q = tube.block(s.q);
  Vec3 nearest = Vec3::Constant(1.0);
  for (int i = 0; i + 1 < tube.pointCount(); ++i) {
    const Vec3 y0 = q.row(i).transpose(), e = q.row(i + 1).transpose() - y0;
    const Vec3 d = x - y0 - std::clamp((x - y0).dot(e) / e.squaredNorm(), 0.0, 1.0) * e;
    if (d.norm() < nearest.norm()) nearest = d;
  }
  return nearest;
}

inline double distanceToAxis(const CurveBody& tube, const SceneState& s, const Vec3& x) {
  return offsetFromAxis(tube, s, x).norm();
}

}  // namespace filum::test
