// bench_mass_solve: the cost of the paper's M A = B resolution (eq. 3), the one linear solve of
// every integrator stage (Scene::computeAcceleration, stage 3b), and of factoring M once.
//
// What it measures, for n = 30, 100, 1000, 10000 control points of a uniform cubic B-spline
// (M banded, half-bandwidth 3, the mass of the hanging-thread scene):
//   - bandedCholeskySolve:   X := B, then X := M⁻¹ X with filum::mechanics::BandedCholesky, the
//                            three coordinates together (B is n × 3, row-major like the state);
//   - simplicialLltSolve:    X = M⁻¹ B with Eigen's SimplicialLLT<SparseMatrix, Lower,
//                            NaturalOrdering> on the same M, same 3 right-hand sides (column-major,
//                            Eigen's preferred layout);
//   - copyRhs:               X := B alone — the copy both solves above include, to subtract;
//   - bandedCholeskyFactor / simplicialLltFactor: building each factorisation from the sparse M
//                            (done once per body, at load time).
// Why: docs/architecture.md, "Numbers that matter", asks for an O(n) per-step solve and the class comment of
// BandedCholesky claims that a hand-written band solver beats the sparse one; these numbers are
// the justification (or not).
//
// How the work stays real: each iteration re-copies the fixed random B into the solution buffer
// before solving (X would otherwise be iterated by M⁻¹ and over- or underflow), exactly as the
// pipeline does with `a = force_; solveMass(a)`; the copy is timed separately (copyRhs) so that
// it can be subtracted. benchmark::DoNotOptimize / ClobberMemory keep the compiler from
// dropping the results. Each setup checks the relative residual |M X − B| / |B| of both solvers.
// items_per_second counts control points (n per iteration).
#include <cstdint>
#include <numbers>

#include <Eigen/SparseCholesky>
#include <benchmark/benchmark.h>

#include "filum/core/types.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"
#include "filum/mechanics/banded_cholesky.hpp"
#include "filum/mechanics/mass_matrix.hpp"

namespace {

using filum::Points;
using filum::SparseMatrix;
using ColMajorSparse = Eigen::SparseMatrix<double, Eigen::ColMajor>;
using Rhs = Eigen::Matrix<double, Eigen::Dynamic, 3>;  // column-major n × 3 for Eigen
using EigenLlt = Eigen::SimplicialLLT<ColMajorSparse, Eigen::Lower, Eigen::NaturalOrdering<int>>;

constexpr int kHalfBandwidth = 3;  // degree of the uniform cubic B-spline

/// Mass of the hanging-thread scene's thread: 910 kg/m³ · π (1e-4 m)² · 0.1 m ≈ 2.86e-6 kg.
double threadMass() { return 910.0 * std::numbers::pi * 1e-4 * 1e-4 * 0.1; }

SparseMatrix massFor(int n) { return filum::mechanics::massMatrix(filum::geometry::UniformCubicBSpline(n), threadMass()); }

/// A fixed, non-trivial right-hand side (Eigen's Random is deterministic without srand).
Points rhsFor(int n) { return Points::Random(n, 3); }

template <class Dense>
double relativeResidual(const SparseMatrix& M, const Dense& X, const Dense& B) {
  const Dense R = M * X - B;
  return R.norm() / B.norm();
}

constexpr double kResidualTolerance = 1e-10;

void bandedCholeskySolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const SparseMatrix M = massFor(n);
  const filum::mechanics::BandedCholesky factor(M, kHalfBandwidth);
  const Points B = rhsFor(n);
  Points X = B;
  factor.solve(X);
  if (relativeResidual(M, X, B) > kResidualTolerance) {
    state.SkipWithError("BandedCholesky: residual too large");
    return;
  }
  for (auto _ : state) {
    X = B;  // same copy as Scene::computeAcceleration's `a = force_` (see copyRhs)
    factor.solve(X);
    benchmark::DoNotOptimize(X.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

void simplicialLltSolve(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const SparseMatrix M = massFor(n);
  const ColMajorSparse Mc = M;
  EigenLlt llt(Mc);
  if (llt.info() != Eigen::Success) {
    state.SkipWithError("SimplicialLLT: factorisation failed");
    return;
  }
  const Rhs B = rhsFor(n);
  Rhs X = llt.solve(B);
  if (relativeResidual(M, X, B) > kResidualTolerance) {
    state.SkipWithError("SimplicialLLT: residual too large");
    return;
  }
  for (auto _ : state) {
    X = llt.solve(B);  // Eigen copies B into X, then solves L and Lᵀ in place: same work shape
    benchmark::DoNotOptimize(X.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

void copyRhs(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const Points B = rhsFor(n);
  Points X(n, 3);
  for (auto _ : state) {
    X = B;
    benchmark::DoNotOptimize(X.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
  state.SetBytesProcessed(state.iterations() * n * 3 * static_cast<std::int64_t>(sizeof(double)));
}

void bandedCholeskyFactor(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const SparseMatrix M = massFor(n);
  for (auto _ : state) {
    filum::mechanics::BandedCholesky factor(M, kHalfBandwidth);
    benchmark::DoNotOptimize(&factor);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

void simplicialLltFactor(benchmark::State& state) {
  const int n = static_cast<int>(state.range(0));
  const ColMajorSparse Mc = massFor(n);
  for (auto _ : state) {
    EigenLlt llt(Mc);  // analyzePattern (trivial ordering, elimination tree) + factorize
    benchmark::DoNotOptimize(&llt);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * n);
}

void controlPointCounts(benchmark::internal::Benchmark* b) {
  for (int n : {30, 100, 1000, 10000}) b->Arg(n);
  b->ArgName("n");
}

}  // namespace

BENCHMARK(bandedCholeskySolve)->Apply(controlPointCounts);
BENCHMARK(simplicialLltSolve)->Apply(controlPointCounts);
BENCHMARK(copyRhs)->Apply(controlPointCounts);
BENCHMARK(bandedCholeskyFactor)->Apply(controlPointCounts);
BENCHMARK(simplicialLltFactor)->Apply(controlPointCounts);
