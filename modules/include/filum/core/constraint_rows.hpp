// ConstraintRows: the constraint system L A = E of the paper (§4): each row is sparse over the
// scene's points with a 3-vector coefficient per point, row·A = Σ_j c_jᵀ A_j. Storage is
// reused from step to step (no allocation once capacity is reached).
#pragma once

#include <vector>

#include "filum/core/types.hpp"

namespace filum {

class ConstraintRows {
 public:
  void clear() {
    start_.assign(1, 0);
    point_.clear();
    coeff_.clear();
    rhs_.clear();
  }
  /// Adds c to the coefficient of global point p in the row being built.
  void addTerm(int p, const Vec3& c) {
    point_.push_back(p);
    coeff_.push_back(c);
  }
  /// Closes the row being built with right-hand side E_r (m/s²).
  void endRow(double rhs) {
    start_.push_back(static_cast<int>(point_.size()));
    rhs_.push_back(rhs);
  }

  int rows() const { return static_cast<int>(rhs_.size()); }
  int begin(int r) const { return start_[r]; }
  int end(int r) const { return start_[r + 1]; }
  int point(int t) const { return point_[t]; }
  const Vec3& coeff(int t) const { return coeff_[t]; }
  double rhs(int r) const { return rhs_[r]; }

  /// L_r · x for a global 3N vector x.
  double dot(int r, const VecX& x) const {
    double sum = 0.0;
    for (int t = start_[r]; t < start_[r + 1]; ++t) sum += coeff_[t].dot(x.segment<3>(3 * point_[t]));
    return sum;
  }
  /// x += w L_rᵀ.
  void addTransposed(int r, double w, VecX& x) const {
    for (int t = start_[r]; t < start_[r + 1]; ++t) x.segment<3>(3 * point_[t]) += w * coeff_[t];
  }

 private:
  std::vector<int> start_{0};
  std::vector<int> point_;
  std::vector<Vec3> coeff_;
  std::vector<double> rhs_;
};

}  // namespace filum
