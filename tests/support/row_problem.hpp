// Constraint rows on one body of a test::BandMatrix, solved once by a fresh LagrangeMultiplierSolver
// with or without its steps through the band (the constraint solver's band tests: deferred W,
// equality rows through the band), and the condition numbers their tolerances are derived from.
#pragma once

#include <Eigen/SVD>

#include "filum/constraints/lagrange_multiplier_solver.hpp"
#include "support/band_matrix.hpp"

namespace filum::test {

/// Rows on one body of `points` points (global indices 0 … points − 1), and the problem they act in.
struct RowProblem {
  ConstraintRows rows;
  ConstraintProblem problem;
  explicit RowProblem(int points) {
    problem.bodies.push_back(BodyBlock{0, points});
    problem.dof_points = points;
    problem.state_size = 3 * points;
    problem.layout_revision = 0;
  }
};

struct RowSolve {
  VecX lambda;
  constraints::LagrangeMultiplierSolver::Statistics stats;
  VecX diagonal;  // W_rr as the solver took it
};

/// The rows solved from a zero acceleration to the contact tolerance `tolerance`; structured =
/// false ("newton_linear_solve": "dense"): W formed and factored, every Newton step by the dense LU.
inline RowSolve solveRows(const RowProblem& p, const BandMatrix& a, bool structured, double tolerance) {
  constraints::LagrangeMultiplierSolver::Options options;
  options.contact_tolerance = tolerance;
  options.newton_structured = structured;
  constraints::LagrangeMultiplierSolver solver(options);
  VecX acceleration = VecX::Zero(p.problem.state_size);
  solver.solve(p.problem, p.rows, a, acceleration);
  return {solver.multipliers(), solver.statistics(), solver.delassusDiagonal()};
}

/// The 2-norm condition number of w (largest over smallest singular value).
inline double condition(const MatX& w) {
  const Eigen::JacobiSVD<MatX> svd(w);
  return svd.singularValues()(0) / svd.singularValues()(w.rows() - 1);
}

/// cond(W + R): R = 1e-6 W_rr on the contact rows, the solver's default compliance.
inline double compliantCondition(const RowProblem& p, const BandMatrix& a) {
  MatX w = delassus(p.rows, a, p.problem);
  for (int r = 0; r < p.rows.rows(); ++r)
    if (p.rows.kind(r) != ConstraintRows::Kind::kEquality) w(r, r) *= 1.0 + 1e-6;
  return condition(w);
}

}  // namespace filum::test
