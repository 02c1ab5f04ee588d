// The generic force-field test (SOFA's force-field test harness is the model; docs/architecture.md,
// "Where new things go": one generic finite-difference test that every force field passes). For
// one field:
//  1. gradient: Q = −∂E/∂q against central differences of potentialEnergy, coordinate by coordinate;
//  2. stiffness: K = ∂Q/∂q from addJacobian(k_factor = 1, d_factor = 0) against central
//     differences of addForce in q, column by column;
//  3. damping: D = ∂Q/∂q̇ from addJacobian(0, 1) against central differences of addForce in q̇.
// Central differences with step h have truncation error h²/6 |f'''| and round-off ε |f| / h; the
// tolerances the tests pass are stated from these two terms, relative to the largest entry of
// the reference (so that a wrong entry of any size shows).
#pragma once

#include <gtest/gtest.h>

#include "filum/core/force_field.hpp"

namespace filum::test {

/// Q of one field at s (3N, N).
inline VecX fieldForce(const ForceField& field, const SceneState& s) {
  VecX B = VecX::Zero(s.q.size());
  field.addForce(s, B);
  return B;
}

/// k_factor K + d_factor D of one field at s, dense (3N × 3N).
inline MatX fieldJacobian(const ForceField& field, const SceneState& s, double k_factor, double d_factor) {
  Triplets triplets;
  TripletAccumulator accumulator(triplets);
  field.addJacobian(s, k_factor, d_factor, accumulator);
  Eigen::SparseMatrix<double> J(s.q.size(), s.q.size());
  J.setFromTriplets(triplets.begin(), triplets.end());
  return MatX(J);
}

struct ForceFieldCheck {
  double h = 1e-6;            // finite-difference step on q (m) and q̇ (m/s)
  double tolerance = 1e-6;    // max |analytic − FD| / max |FD|
  bool gradient = true;       // the field has a potential (skip for dissipative fields)
  bool stiffness = true;      // compare K (skip when addJacobian documents an omitted ∂Q/∂q)
  bool damping = true;        // compare D
};

/// Runs the checks of `check` on `field` at state s; returns the worst relative errors
/// (gradient, stiffness, damping), each also checked with EXPECT.
inline Eigen::Vector3d expectForceFieldConsistent(const ForceField& field, const SceneState& s,
                                                  const ForceFieldCheck& check) {
  const Eigen::Index n = s.q.size();
  Eigen::Vector3d worst = Eigen::Vector3d::Zero();
  const VecX Q = fieldForce(field, s);

  if (check.gradient) {
    VecX fd(n);
    for (Eigen::Index j = 0; j < n; ++j) {
      SceneState p = s, m = s;
      p.q[j] += check.h;
      m.q[j] -= check.h;
      fd[j] = -(field.potentialEnergy(p) - field.potentialEnergy(m)) / (2.0 * check.h);  // −∂E/∂q_j
    }
    worst[0] = (Q - fd).cwiseAbs().maxCoeff() / std::max(fd.cwiseAbs().maxCoeff(), 1e-300);
    EXPECT_LE(worst[0], check.tolerance) << field.describe() << ": force is not −∂E/∂q";
  }
  for (int which = 0; which < 2; ++which) {
    if ((which == 0 && !check.stiffness) || (which == 1 && !check.damping)) continue;
    const MatX J = fieldJacobian(field, s, which == 0 ? 1.0 : 0.0, which == 0 ? 0.0 : 1.0);
    MatX fd(n, n);
    for (Eigen::Index j = 0; j < n; ++j) {
      SceneState p = s, m = s;
      (which == 0 ? p.q : p.v)[j] += check.h;
      (which == 0 ? m.q : m.v)[j] -= check.h;
      fd.col(j) = (fieldForce(field, p) - fieldForce(field, m)) / (2.0 * check.h);
    }
    const double scale = fd.cwiseAbs().maxCoeff();
    worst[1 + which] = scale > 0.0 ? (J - fd).cwiseAbs().maxCoeff() / scale : J.cwiseAbs().maxCoeff();
    EXPECT_LE(worst[1 + which], check.tolerance)
        << field.describe() << (which == 0 ? ": K = ∂Q/∂q" : ": D = ∂Q/∂q̇") << " differs from finite differences";
  }
  return worst;
}

}  // namespace filum::test
