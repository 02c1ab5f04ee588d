// SparseLdlt: factorization of a sparse symmetric matrix that is not banded — the step matrix
// M − θh D − κh² K of several coupled bodies, or of one body whose energy couples distant
// control points (the paper's global stretching, whose Hessian holds the dense rank-one term
// ∇l ∇lᵀ). docs/architecture.md, "Numbers that matter": "Large sparse systems go to SuiteSparse
// (CHOLMOD) through Eigen's wrappers". With FILUM_WITH_SUITESPARSE (CMake option, default ON)
// this is CHOLMOD (supernodal LLᵀ, switching to LDLᵀ when the matrix is indefinite); without it,
// Eigen's SimplicialLDLT.
//
// precompute/solve split (libigl style): the symbolic analysis is redone only when the sparsity
// pattern changes; the numeric factorization is redone on every factor().
#pragma once

#include <memory>
#include <string>

#include "filum/core/types.hpp"

namespace filum::mechanics {

class SparseLdlt {
 public:
  using Matrix = Eigen::SparseMatrix<double>;  // column major, as CHOLMOD wants

  SparseLdlt();
  ~SparseLdlt();
  SparseLdlt(SparseLdlt&&) noexcept;
  SparseLdlt& operator=(SparseLdlt&&) noexcept;

  /// Factors the symmetric matrix whose lower triangle is `lower` (the upper part is ignored).
  /// `pattern_changed`: the sparsity pattern differs from the previous call's. Returns "" on
  /// success, else the reason (not factorizable).
  std::string factor(const Matrix& lower, bool pattern_changed);
  /// In place x := A⁻¹ x.
  void solve(Eigen::Ref<VecX> x) const;

  /// "CHOLMOD supernodal LLt", "CHOLMOD LDLt" or "Eigen SimplicialLDLT".
  std::string method() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace filum::mechanics
