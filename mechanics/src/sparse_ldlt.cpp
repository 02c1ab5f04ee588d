#include "filum/mechanics/sparse_ldlt.hpp"

#ifdef FILUM_WITH_SUITESPARSE
#include <Eigen/CholmodSupport>
#else
#include <Eigen/SparseCholesky>
#endif

namespace filum::mechanics {

#ifdef FILUM_WITH_SUITESPARSE

struct SparseLdlt::Impl {
  // Supernodal LLᵀ is CHOLMOD's fastest path but needs a positive definite matrix; an implicit
  // step with a compressed (negative) stiffness may not be, then CHOLMOD's simplicial LDLᵀ
  // (no pivoting, like BlockBandLdlt) takes over for the rest of the run.
  Eigen::CholmodDecomposition<SparseLdlt::Matrix, Eigen::Lower> solver;
  bool ldlt = false;

  // An indefinite matrix is an expected case (handled by switching to LDLᵀ), not a warning to
  // print on stderr: CHOLMOD prints nothing, filum reports.
  Impl() { solver.cholmod().print = 0; }
  bool analyzed = false;
  mutable VecX rhs;

  std::string factor(const SparseLdlt::Matrix& lower, bool pattern_changed) {
    if (!analyzed || pattern_changed) {
      solver.setMode(ldlt ? Eigen::CholmodLDLt : Eigen::CholmodSupernodalLLt);
      solver.analyzePattern(lower);
      analyzed = true;
    }
    solver.factorize(lower);
    if (solver.info() == Eigen::Success) return "";
    if (!ldlt) {  // not positive definite: retry once as LDLᵀ
      ldlt = true;
      solver.setMode(Eigen::CholmodLDLt);
      solver.analyzePattern(lower);
      solver.factorize(lower);
      if (solver.info() == Eigen::Success) return "";
    }
    return "CHOLMOD could not factor the step matrix (singular)";
  }
  void solve(Eigen::Ref<VecX> x) const {
    rhs = x;
    x = solver.solve(rhs);
  }
  std::string method() const { return ldlt ? "CHOLMOD LDLt" : "CHOLMOD supernodal LLt"; }
};

#else

struct SparseLdlt::Impl {
  Eigen::SimplicialLDLT<SparseLdlt::Matrix, Eigen::Lower> solver;
  bool analyzed = false;
  mutable VecX rhs;

  std::string factor(const SparseLdlt::Matrix& lower, bool pattern_changed) {
    if (!analyzed || pattern_changed) {
      solver.analyzePattern(lower);
      analyzed = true;
    }
    solver.factorize(lower);
    return solver.info() == Eigen::Success ? "" : "SimplicialLDLT could not factor the step matrix (singular)";
  }
  void solve(Eigen::Ref<VecX> x) const {
    rhs = x;
    x = solver.solve(rhs);
  }
  std::string method() const { return "Eigen SimplicialLDLT"; }
};

#endif

SparseLdlt::SparseLdlt() : impl_(std::make_unique<Impl>()) {}
SparseLdlt::~SparseLdlt() = default;
SparseLdlt::SparseLdlt(SparseLdlt&&) noexcept = default;
SparseLdlt& SparseLdlt::operator=(SparseLdlt&&) noexcept = default;

std::string SparseLdlt::factor(const Matrix& lower, bool pattern_changed) {
  return impl_->factor(lower, pattern_changed);
}
void SparseLdlt::solve(Eigen::Ref<VecX> x) const { impl_->solve(x); }
std::string SparseLdlt::method() const { return impl_->method(); }

}  // namespace filum::mechanics
