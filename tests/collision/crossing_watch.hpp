// CrossingWatch: do threads pass through each other or through themselves? Independent of the
// contact pipeline: every thread is sampled at fixed abscissas (kSamples per thread, so that the
// polylines follow the material, not the pipeline's resampled spheres), and for every pair of
// polyline segments that are not neighbours along a thread
//   1. the segments never meet while they move linearly from one step's samples to the next
//      (edge–edge continuous test, segment_continuous_collision.hpp, tolerance 1e-12 m), and
//   2. the sign of the signed distance between their lines is the same at consecutive steps
//      for every pair that stays close (distance < 3 thread diameters, closest points inside
//      both segments): that sign flips exactly when one centre line passes through the other.
// Candidate pairs come from the uniform grid (exact against brute force, broad_phase_test.cpp)
// over bounding spheres that cover each segment at both steps plus 10 radii. The smallest
// distance between centre lines is reported; the contact distance is 2r.
#pragma once

#include <algorithm>
#include <limits>
#include <map>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "filum/collision/segment_closest_points.hpp"
#include "filum/collision/segment_continuous_collision.hpp"
#include "filum/collision/uniform_grid_broad_phase.hpp"
#include "filum/core/scene.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::test {

constexpr int kSamples = 120;

struct CrossingWatch {
  double min_distance = std::numeric_limits<double>::infinity();
  int crossings = 0;        // segment pairs that met between two steps
  int sign_flips = 0;       // close pairs whose crossing sign changed
  long close_pairs = 0;     // pair-steps compared for the sign
  std::map<std::pair<int, int>, double> sign;  // signed line distance of close pairs at the last step
  std::vector<collision::BoundingSphere> bounds;
  std::vector<collision::IndexPair> candidates;
  collision::UniformGridBroadPhase grid;

  /// Polylines of every thread at state s (samples each), concatenated.
  static Points sample(const Scene& scene, const SceneState& s, int samples = kSamples) {
    const int bodies = static_cast<int>(scene.bodies().size());
    Points all(bodies * samples, 3);
    for (int b = 0; b < bodies; ++b) {
      const auto& spline = *scene.bodies()[b]->curve();
      all.middleRows(b * samples, samples) = geometry::sampleCurve(spline.basis(), spline.block(s.q), samples);
    }
    return all;
  }

  /// Compares the polylines of two consecutive steps (`samples` points per thread). Segments of
  /// one thread closer than `neighbours` samples are not checked (they touch through the curve).
  void check(const Points& before, const Points& after, int neighbours, double radius, int samples = kSamples) {
    const int total = static_cast<int>(before.rows());
    bounds.resize(total);
    for (int i = 0; i + 1 < total; ++i) {
      const Vec3 a0 = before.row(i).transpose(), a1 = before.row(i + 1).transpose();
      const Vec3 c0 = after.row(i).transpose(), c1 = after.row(i + 1).transpose();
      const Vec3 center = 0.25 * (a0 + a1 + c0 + c1);
      const double reach = std::max({(a0 - center).norm(), (a1 - center).norm(), (c0 - center).norm(), (c1 - center).norm()});
      bounds[i] = {center, reach + 5.0 * radius};
    }
    bounds[total - 1] = {after.row(total - 1).transpose(), 0.0};  // no segment starts at the last point
    grid.findPairs(bounds, candidates);
    std::map<std::pair<int, int>, double> next_sign;  // only pairs close at this step carry over
    for (const auto& [i, j] : candidates) {
      if ((i + 1) % samples == 0 || (j + 1) % samples == 0) continue;  // no segment between two threads
      if (i / samples == j / samples && j - i < std::max(neighbours, 2)) continue;
      const Vec3 a0 = before.row(i).transpose(), a1 = before.row(i + 1).transpose();
      const Vec3 b0 = before.row(j).transpose(), b1 = before.row(j + 1).transpose();
      const Vec3 c0 = after.row(i).transpose(), c1 = after.row(i + 1).transpose();
      const Vec3 d0 = after.row(j).transpose(), d1 = after.row(j + 1).transpose();
      const collision::SegmentClosestPoints now = collision::closestPointsOnSegments(c0, c1, d0, d1);
      min_distance = std::min(min_distance, now.distance);
      if (collision::firstSegmentContact({a0, a1, c0, c1}, {b0, b1, d0, d1}, 1e-12)) ++crossings;
      // Crossing sign of close pairs with interior closest points.
      const bool close = now.distance < 6.0 * radius && now.s > 0.0 && now.s < 1.0 && now.t > 0.0 && now.t < 1.0;
      const auto key = std::make_pair(i, j);
      if (close) {
        const double signed_distance = collision::signedLineDistance(c0, c1, d0, d1);
        const auto it = sign.find(key);
        if (it != sign.end()) {
          ++close_pairs;
          if ((it->second > 0.0) != (signed_distance > 0.0)) ++sign_flips;
        }
        next_sign[key] = signed_distance;
      }
    }
    sign.swap(next_sign);
  }
};

/// Runs the scene for `steps` steps and watches every pair of segments.
inline CrossingWatch watch(Scene& scene, long steps, int neighbours, double radius, int samples = kSamples) {
  CrossingWatch w;
  Points before = CrossingWatch::sample(scene, scene.state(), samples);
  for (long k = 0; k < steps; ++k) {
    const StepReport r = scene.step();
    EXPECT_TRUE(r.ok) << r.message;
    if (!r.ok) break;
    const Points after = CrossingWatch::sample(scene, scene.state(), samples);
    w.check(before, after, neighbours, radius, samples);
    before = after;
  }
  return w;
}

}  // namespace filum::test
