// Knot vectors of B-splines of degree d (de Boor, "A Practical Guide to Splines", ch. IX;
// Piegl & Tiller, "The NURBS Book", §2.2): validation, the span containing a parameter
// (Piegl & Tiller algorithm A2.1), knot multiplicities and the usual uniform knot vectors.
//
// Conventions used by every geometry function:
//   knots t_0 <= t_1 <= ... <= t_{n+d}  (n + d + 1 values for n control points),
//   B-spline basis functions B_{i,d}, i = 0..n−1, B_{i,d} supported on [t_i, t_{i+d+1}],
//   valid domain [t_d, t_n] (where Σ_i B_{i,d} = 1); it is mapped affinely onto s ∈ [0, 1]:
//     u(s) = t_d + s (t_n − t_d).
#pragma once

#include <vector>

namespace filum::geometry {

inline constexpr int kMinimumSplineDegree = 1;
inline constexpr int kMaximumSplineDegree = 5;  // BasisRow holds at most degree + 1 = 6 functions

/// Throws std::invalid_argument unless `knots` is a valid knot vector of degree `degree` for
/// `control_points` control points:
///  - 1 <= degree <= 5 and control_points >= degree + 1,
///  - knots.size() == control_points + degree + 1, all finite, non-decreasing,
///  - no knot of multiplicity above degree + 1 (a B-spline would vanish identically),
///  - t_d < t_{d+1} and t_{n−1} < t_n (every basis function is non-zero somewhere in the
///    domain; this also makes the domain [t_d, t_n] non-empty).
/// `what` prefixes the error message (e.g. the caller's name).
void validateKnotVector(int degree, int control_points, const std::vector<double>& knots,
                        const char* what = "knot vector");

/// Span index k with t_k <= u < t_{k+1} and d <= k <= n − 1 (Piegl & Tiller A2.1, binary
/// search); u is clamped to [t_d, t_n], and u = t_n returns the last non-empty span.
/// Precondition: a validated knot vector.
int findKnotSpan(int degree, int control_points, const std::vector<double>& knots, double u);

/// Number of knots equal to u (exact comparison).
int knotMultiplicity(const std::vector<double>& knots, double u);

/// Distinct knot values in the domain [t_d, t_n], sorted (t_d and t_n included).
std::vector<double> distinctDomainKnots(int degree, int control_points, const std::vector<double>& knots);

/// Uniform (unclamped) knots t_i = i − d, i = 0..n+d: domain [0, n − d], n − d pieces.
/// For degree 3 this is exactly the uniform cubic B-spline (UniformCubicBSpline).
std::vector<double> uniformKnots(int degree, int control_points);

/// Clamped (open) uniform knots: 0 repeated d + 1 times, 1..(n−d−1), (n − d) repeated d + 1
/// times. The curve interpolates its first and last control points.
std::vector<double> clampedUniformKnots(int degree, int control_points);

}  // namespace filum::geometry
