// bench_geometry: throughput of the geometry library (filum::geometry), the inner loops of every
// mapping, force field and collision query on a spline.
//
//  - BM_CurvePoint/<basis>:   P(s) = Σ b_i(s) q_i at pseudo-random abscissas (basis row + sum),
//  - BM_BasisRow/<basis>:     the basis row alone (values, first and second derivatives),
//    for the uniform cubic B-spline, Catmull-Rom, and NUBS of degree 3 (clamped uniform knots and
//    random knots) and degree 5; n = 30 control points (the paper's thread). items_per_second =
//    evaluations per second.
//  - BM_InsertKnotsOslo/n/k:  inserting k random knots at once into an n-point cubic NUBS (Oslo),
//  - BM_InsertKnotsBoehm/n/k: the same knots one at a time (Boehm), for comparison,
//  - BM_CurveLength, BM_ClosestPoint, BM_ConvolutionField: one call each, for scale.
//
// Run: build-geometry/apps/bench/bench_geometry --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include <benchmark/benchmark.h>

#include <memory>
#include <random>
#include <vector>

#include "filum/geometry/arc_length.hpp"
#include "filum/geometry/bspline_curve.hpp"
#include "filum/geometry/catmull_rom_spline.hpp"
#include "filum/geometry/closest_point.hpp"
#include "filum/geometry/convolution_surface.hpp"
#include "filum/geometry/knot_insertion.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"

namespace {

using namespace filum;
using namespace filum::geometry;

constexpr int kControlPoints = 30;

Points randomPoints(int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  Points p(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p(i, k) = u(rng);
  return p;
}

/// Knots of degree d for n points: clamped, interior gaps random in [0.2, 2].
std::vector<double> randomClampedKnots(int d, int n, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> gap(0.2, 2.0);
  std::vector<double> t(d + 1, 0.0);
  double x = 0.0;
  while (static_cast<int>(t.size()) < n) t.push_back(x += gap(rng));
  t.insert(t.end(), d + 1, x + gap(rng));
  return t;
}

std::unique_ptr<CurveBasis> makeBasis(int which, int n) {
  switch (which) {
    case 0: return std::make_unique<UniformCubicBSpline>(n);
    case 1: return std::make_unique<CatmullRomSpline>(n);
    case 2: return std::make_unique<NonUniformBSpline>(3, clampedUniformKnots(3, n));
    case 3: return std::make_unique<NonUniformBSpline>(3, randomClampedKnots(3, n, 7));
    default: return std::make_unique<NonUniformBSpline>(5, randomClampedKnots(5, n, 8));
  }
}

const char* basisLabel(int which) {
  static const char* labels[] = {"uniform_cubic", "catmull_rom", "nubs3_uniform", "nubs3_random", "nubs5_random"};
  return labels[which];
}

std::vector<double> randomAbscissas(int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> s(count);
  for (double& x : s) x = u(rng);
  return s;
}

void BM_CurvePoint(benchmark::State& state) {
  const auto basis = makeBasis(static_cast<int>(state.range(0)), kControlPoints);
  const Points q = randomPoints(kControlPoints, 1);
  const std::vector<double> s = randomAbscissas(1024, 2);
  BasisRow row;
  std::size_t k = 0;
  for (auto _ : state) {
    basis->evaluate(s[k++ & 1023], row);
    Vec3 p = curvePoint(row, q);
    benchmark::DoNotOptimize(p);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(basisLabel(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_CurvePoint)->DenseRange(0, 4);

void BM_BasisRow(benchmark::State& state) {
  const auto basis = makeBasis(static_cast<int>(state.range(0)), kControlPoints);
  const std::vector<double> s = randomAbscissas(1024, 3);
  BasisRow row;
  std::size_t k = 0;
  for (auto _ : state) {
    basis->evaluate(s[k++ & 1023], row);
    benchmark::DoNotOptimize(row);
  }
  state.SetItemsProcessed(state.iterations());
  state.SetLabel(basisLabel(static_cast<int>(state.range(0))));
}
BENCHMARK(BM_BasisRow)->DenseRange(0, 4);

std::vector<double> randomDomainKnots(const BSplineCurve& c, int k, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(c.knots[c.degree], c.knots[c.controlPointCount()]);
  std::vector<double> out(k);
  for (double& x : out) x = u(rng);
  return out;
}

void BM_InsertKnotsOslo(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const BSplineCurve curve{3, randomClampedKnots(3, n, 4), randomPoints(n, 5)};
  const std::vector<double> extra = randomDomainKnots(curve, k, 6);
  for (auto _ : state) {
    BSplineCurve refined = insertKnots(curve, extra);
    benchmark::DoNotOptimize(refined.control_points.data());
  }
  state.counters["knots_inserted"] = k;
}
BENCHMARK(BM_InsertKnotsOslo)->ArgsProduct({{30, 165}, {1, 10, 100}})->Unit(benchmark::kMicrosecond);

void BM_InsertKnotsBoehm(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0)), k = static_cast<int>(state.range(1));
  const BSplineCurve curve{3, randomClampedKnots(3, n, 4), randomPoints(n, 5)};
  const std::vector<double> extra = randomDomainKnots(curve, k, 6);
  for (auto _ : state) {
    BSplineCurve refined = curve;
    for (double u : extra) refined = insertKnot(refined, u);
    benchmark::DoNotOptimize(refined.control_points.data());
  }
  state.counters["knots_inserted"] = k;
}
BENCHMARK(BM_InsertKnotsBoehm)->ArgsProduct({{30, 165}, {1, 10, 100}})->Unit(benchmark::kMicrosecond);

void BM_CurveLength(benchmark::State& state) {
  const UniformCubicBSpline basis(kControlPoints);
  const Points q = randomPoints(kControlPoints, 9);
  for (auto _ : state) benchmark::DoNotOptimize(curveLength(basis, q, 1e-10));
}
BENCHMARK(BM_CurveLength)->Unit(benchmark::kMicrosecond);

void BM_ClosestPoint(benchmark::State& state) {
  const UniformCubicBSpline basis(kControlPoints);
  const Points q = randomPoints(kControlPoints, 10);
  const Points x = randomPoints(256, 11);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(closestPoint(basis, q, x.row(k++ & 255).transpose()));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ClosestPoint)->Unit(benchmark::kMicrosecond);

void BM_ConvolutionField(benchmark::State& state) {
  // A thread of 30 control points skinned as 64 chords; field and gradient at one point.
  const UniformCubicBSpline basis(kControlPoints);
  const Points q = randomPoints(kControlPoints, 12);
  ConvolutionSurface surface(0.05);
  surface.addCurve(basis, q, 64);
  const Points x = randomPoints(256, 13);
  std::size_t k = 0;
  for (auto _ : state) benchmark::DoNotOptimize(surface.fieldAndGradient(x.row(k++ & 255).transpose()));
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ConvolutionField);

}  // namespace
