// Shared fixtures of the geometry tests: deterministic random knot vectors, curves and the list
// of bases every generic property is checked on.
#pragma once

#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/bspline_curve.hpp"
#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_basis.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace filum::geometry::test {

/// n points with coordinates uniform in [-scale, scale].
inline Points randomControlPoints(int n, std::mt19937& rng, double scale = 1.0) {
  std::uniform_real_distribution<double> u(-scale, scale);
  Points p(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p(i, k) = u(rng);
  return p;
}

/// A random valid knot vector of degree d for n control points: random gaps in [0.2, 2], some
/// interior knots repeated (multiplicity up to max_multiplicity <= d + 1), clamped or not.
inline std::vector<double> randomKnots(int d, int n, bool clamped, std::mt19937& rng, int max_multiplicity = 2) {
  std::uniform_real_distribution<double> gap(0.2, 2.0), coin(0.0, 1.0);
  const int total = n + d + 1;
  std::vector<double> t;
  t.reserve(total);
  double x = std::uniform_real_distribution<double>(-3.0, 3.0)(rng);
  if (clamped) t.assign(d + 1, x);
  else t.push_back(x);
  const int interior_end = clamped ? total - (d + 1) : total;
  while (static_cast<int>(t.size()) < interior_end) {
    x += gap(rng);
    int copies = 1;
    if (max_multiplicity > 1 && coin(rng) < 0.25)
      copies = std::uniform_int_distribution<int>(2, max_multiplicity)(rng);
    copies = std::min(copies, interior_end - static_cast<int>(t.size()));
    t.insert(t.end(), copies, x);
  }
  if (clamped) {
    x += gap(rng);
    t.insert(t.end(), d + 1, x);
  }
  return t;  // may have a repeated knot at a domain end: randomCurve retries then
}

/// A random valid NUBS curve (retries until the knot vector validates).
inline BSplineCurve randomCurve(int d, int n, bool clamped, std::mt19937& rng, int max_multiplicity = 2) {
  for (;;) {
    std::vector<double> t = randomKnots(d, n, clamped, rng, max_multiplicity);
    try {
      validateKnotVector(d, n, t);
    } catch (const std::invalid_argument&) {
      continue;
    }
    return BSplineCurve{d, std::move(t), randomControlPoints(n, rng)};
  }
}

struct NamedBasis {
  std::string label;
  std::shared_ptr<CurveBasis> basis;
  bool non_negative;  // B-splines yes, Catmull-Rom no
};

/// Every kind of basis, several sizes, degrees, clamped and unclamped, with repeated knots.
inline std::vector<NamedBasis> allTestBases() {
  std::vector<NamedBasis> out;
  for (int n : {4, 7, 20}) out.push_back({"uniform_cubic_n" + std::to_string(n), std::make_shared<UniformCubicBSpline>(n), true});
  for (int n : {4, 11}) out.push_back({"catmull_rom_n" + std::to_string(n), std::make_shared<CatmullRomSpline>(n), false});
  std::mt19937 rng(20240611);
  for (int d = 1; d <= 5; ++d) {
    const int n = d + 1 + 2 * d;
    out.push_back({"nubs_clamped_uniform_d" + std::to_string(d), std::make_shared<NonUniformBSpline>(d, clampedUniformKnots(d, n)), true});
    out.push_back({"nubs_random_clamped_d" + std::to_string(d),
                   std::make_shared<NonUniformBSpline>(d, randomCurve(d, n, true, rng, d + 1).knots), true});
    out.push_back({"nubs_random_open_d" + std::to_string(d),
                   std::make_shared<NonUniformBSpline>(d, randomCurve(d, n, false, rng, d).knots), true});
  }
  return out;
}

/// Max over `count` random abscissas (fixed seed) of |P_a(s) − P_b(s)|.
template <class A, class B>
double maxDeviation(const A& pa, const B& pb, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double worst = 0.0;
  for (int k = 0; k < count; ++k) {
    const double s = k == 0 ? 0.0 : (k == 1 ? 1.0 : u(rng));
    worst = std::max(worst, (pa(s) - pb(s)).norm());
  }
  return worst;
}

}  // namespace filum::geometry::test
