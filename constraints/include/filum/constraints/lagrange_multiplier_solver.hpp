// LagrangeMultiplierSolver: bilateral constraints by the acceleration decomposition (paper §4,
// talk 002 "fallopian tubes"):
//   M A_t = B                      (tendency acceleration, done by the scene)
//   (L M⁻¹ Lᵀ) λ = E − L A_t       (c × c Delassus system)
//   A = A_t + M⁻¹ Lᵀ λ
// Each row of L touches only the d + 1 control points whose basis is non-zero at its abscissa,
// and M⁻¹ Lᵀ is computed column by column with the body's O(n) band solve, so a step costs
// O(c n + c² d + c³) instead of the paper's O(c n² + c² n + c³). M may be any block-diagonal
// system matrix given as a BlockInverse (implicit steps use M − h D − h² K).
#pragma once

#include <memory>
#include <vector>

#include <Eigen/Cholesky>

#include "filum/core/constraint_solver.hpp"
#include "filum/core/params.hpp"

namespace filum::constraints {

class LagrangeMultiplierSolver final : public ConstraintSolver {
 public:
  static std::unique_ptr<LagrangeMultiplierSolver> fromParams(const Params&) {
    return std::make_unique<LagrangeMultiplierSolver>();
  }
  std::string typeName() const override { return "LagrangeMultiplierSolver"; }
  void solve(const Scene& scene, const ConstraintRows& rows, const BlockInverse& inverse, VecX& a) override;

  /// Multipliers of the last solve (N for a fixed point: the force holding it).
  const VecX& multipliers() const { return lambda_; }

 private:
  MatX y_;       // M⁻¹ Lᵀ (3N × c)
  MatX w_;       // L M⁻¹ Lᵀ (c × c)
  VecX rhs_, lambda_;
  Eigen::LDLT<MatX> ldlt_;
  std::vector<int> touched_;  // bodies touched by the current row
};

}  // namespace filum::constraints
