#include "filum/mechanics/curve_quadrature.hpp"

#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::mechanics {

CurveQuadrature::CurveQuadrature(const CurveBasis& basis, int nodes_per_piece, ConstPointsRef initial,
                                 std::optional<double> rest_length) {
  const geometry::QuadratureRule rule = geometry::gaussLegendre(nodes_per_piece);
  const std::vector<double> pieces = basis.breakpoints();
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k) {
    const double a = pieces[k], b = pieces[k + 1];
    if (b <= a) continue;
    const double half = 0.5 * (b - a), mid = 0.5 * (a + b);
    for (std::size_t g = 0; g < rule.nodes.size(); ++g) {
      QuadratureNode node;
      node.s = mid + half * rule.nodes[g];
      node.weight = half * rule.weights[g];
      basis.evaluate(node.s, node.row);
      node.rest_speed = rest_length ? *rest_length : geometry::curveTangent(node.row, initial).norm();
      rest_length_ += node.weight * node.rest_speed;
      nodes_.push_back(node);
    }
  }
  for (std::size_t g = 0; g < nodes_.size(); ++g) {
    const geometry::BasisRow& row = nodes_[g].row;
    if (pieces_.empty() || pieces_.back().first != row.first || pieces_.back().count != row.count)
      pieces_.push_back({row.first, row.count, static_cast<int>(g), static_cast<int>(g)});
    pieces_.back().end = static_cast<int>(g) + 1;
  }
}

}  // namespace filum::mechanics
