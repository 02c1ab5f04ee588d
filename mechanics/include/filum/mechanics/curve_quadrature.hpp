// CurveQuadrature: the Gauss-Legendre nodes of every polynomial piece of a spline basis, with the
// basis row (b_i, b'_i, b''_i) and the rest speed |P0'(s)| at each node, computed once (model
// data, docs/architecture.md, "Model and state"). Continuous energies integrate with it:
//   ∫_0^1 f(s) ds ≈ Σ_g w_g f(s_g),
// exact when f is a polynomial of degree <= 2k − 1 on each piece (k nodes per piece).
//
// The rest configuration. A thread has no rest shape but it has a rest length: the material
// point of abscissa s sits at rest arc length σ(s) = ∫_0^s |P0'| ds. By default P0 is the initial
// curve; with a rest length ℓ0 the rest configuration is a straight thread of length ℓ0
// parametrized uniformly, |P0'(s)| = ℓ0 (slack or pre-stretched threads: catenary, taut string).
#pragma once

#include <optional>
#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::mechanics {

struct QuadratureNode {
  double s = 0.0;           // abscissa in [0, 1]
  double weight = 0.0;      // w_g (sums to 1 over the curve)
  double rest_speed = 0.0;  // |P0'(s_g)| (m per unit of s)
  geometry::BasisRow row;   // b, b', b'' at s_g
};

/// Consecutive nodes that share one support (a polynomial piece): nodes [begin, end) act on the
/// points first .. first + count − 1 of the body.
struct QuadraturePiece {
  int first = 0, count = 0, begin = 0, end = 0;
};

class CurveQuadrature {
 public:
  CurveQuadrature() = default;
  /// nodes_per_piece >= 1 Gauss-Legendre nodes on each polynomial piece; rest speeds from
  /// `initial` (n × 3) or, if rest_length is given (m, > 0), uniform |P0'| = rest_length.
  CurveQuadrature(const CurveBasis& basis, int nodes_per_piece, ConstPointsRef initial,
                  std::optional<double> rest_length);

  const std::vector<QuadratureNode>& nodes() const { return nodes_; }
  /// The nodes grouped by support, in order.
  const std::vector<QuadraturePiece>& pieces() const { return pieces_; }
  /// ℓ0 = Σ_g w_g |P0'(s_g)| (m).
  double restLength() const { return rest_length_; }

 private:
  std::vector<QuadratureNode> nodes_;
  std::vector<QuadraturePiece> pieces_;
  double rest_length_ = 0.0;
};

/// The default number of nodes per piece for an energy in P' of a degree-d spline: the
/// Green-Lagrange density ε² has degree 4(d − 1) on a piece, integrated exactly by 2d − 1 nodes.
inline int defaultNodesPerPiece(int degree) { return degree > 1 ? 2 * degree - 1 : 1; }

}  // namespace filum::mechanics
