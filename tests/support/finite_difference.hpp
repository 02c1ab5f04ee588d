// Finite-difference checks shared by the test suites (SOFA's generic mapping and force-field
// tests are the model). Central differences have truncation error h²/6 |f'''| and round-off
// ε |f| / h; tolerances in the tests are stated from these two terms.
#pragma once

#include <random>

#include <gtest/gtest.h>

#include "filum/core/mapping.hpp"

namespace filum::test {

/// Random points with coordinates uniform in [-scale, scale] (deterministic from seed).
inline Points randomPoints(int n, double scale, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-scale, scale);
  Points p(n, 3);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p(i, k) = u(rng);
  return p;
}

/// The generic mapping test:
///  1. ⟨applyJ(v), f⟩ = ⟨v, applyJT(f)⟩ for random v, f (transpose consistency), to `tolerance`
///     relative to |v||f|;
///  2. applyJ(v) matches the central difference (apply(x + h v) − apply(x − h v)) / 2h;
///  3. jacobian() times v matches applyJ(v).
inline void expectMappingConsistent(const Mapping& mapping, ConstPointsRef x, double h, double tolerance,
                                    unsigned seed = 1) {
  const int nin = mapping.inputCount(), nout = mapping.outputCount();
  const Points v = randomPoints(nin, 1.0, seed);
  const Points f = randomPoints(nout, 1.0, seed + 1);

  Points jv(nout, 3), jtf = Points::Zero(nin, 3);
  mapping.applyJ(x, v, jv);
  mapping.applyJT(x, f, jtf);
  const double lhs = jv.cwiseProduct(f).sum(), rhs = v.cwiseProduct(jtf).sum();
  EXPECT_NEAR(lhs, rhs, tolerance * v.norm() * f.norm()) << "applyJT is not the transpose of applyJ";

  Points plus(nout, 3), minus(nout, 3);
  mapping.apply(x + h * v, plus);
  mapping.apply(x - h * v, minus);
  const Points fd = (plus - minus) / (2.0 * h);
  EXPECT_LE((fd - jv).norm(), tolerance * (1.0 + jv.norm())) << "applyJ differs from finite differences of apply";

  const SparseMatrix J = mapping.jacobian(x);
  ASSERT_EQ(J.rows(), 3 * nout);
  ASSERT_EQ(J.cols(), 3 * nin);
  const VecX vflat = Eigen::Map<const VecX>(v.data(), 3 * nin);
  const VecX jflat = J * vflat;
  EXPECT_LE((jflat - Eigen::Map<const VecX>(jv.data(), 3 * nout)).norm(), tolerance * (1.0 + jv.norm()))
      << "jacobian() differs from applyJ";
}

}  // namespace filum::test
