#include "filum/mechanics/mass_matrix.hpp"

#include <vector>

#include "filum/geometry/gauss_legendre.hpp"

namespace filum::mechanics {

namespace {

/// Calls f(s, weight, row) for every quadrature node of every polynomial piece.
template <class F>
void forEachNode(const CurveBasis& basis, int nodes_per_piece, F&& f) {
  const geometry::QuadratureRule rule = geometry::gaussLegendre(nodes_per_piece);
  const std::vector<double> pieces = basis.breakpoints();
  geometry::BasisRow row;
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    const double a = pieces[k], b = pieces[k + 1];
    if (b <= a) continue;
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    for (std::size_t g = 0; g < rule.nodes.size(); ++g) {
      basis.evaluate(mid + half * rule.nodes[g], row);
      f(half * rule.weights[g], row);
    }
  }
}

}  // namespace

SparseMatrix massMatrix(const CurveBasis& basis, double mass) {
  const int n = basis.controlPointCount();
  std::vector<Eigen::Triplet<double>> entries;
  forEachNode(basis, basis.degree() + 1, [&](double w, const geometry::BasisRow& row) {
    // Each product once, mirrored, so that M is symmetric to the last bit.
    for (int a = 0; a < row.count; ++a)
      for (int b = a; b < row.count; ++b) {
        const double value = mass * w * row.value[a] * row.value[b];
        entries.emplace_back(row.first + a, row.first + b, value);
        if (b != a) entries.emplace_back(row.first + b, row.first + a, value);
      }
  });
  SparseMatrix M(n, n);
  M.setFromTriplets(entries.begin(), entries.end());
  return M;
}

VecX basisIntegrals(const CurveBasis& basis) {
  VecX w = VecX::Zero(basis.controlPointCount());
  forEachNode(basis, basis.degree() + 1, [&](double weight, const geometry::BasisRow& row) {
    for (int a = 0; a < row.count; ++a) w[row.first + a] += weight * row.value[a];
  });
  return w;
}

}  // namespace filum::mechanics
