// Properties every CurveBasis must have, checked on every kind of basis (uniform cubic
// B-spline, Catmull-Rom, NUBS of degree 1..5 on uniform, random clamped and random unclamped
// knots with repeated knots): partition of unity, non-negativity (B-splines), local support,
// polynomial pieces between breakpoints, derivatives against finite differences, continuity.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <algorithm>
#include <random>

#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "geometry/spline_test_support.hpp"

namespace filum::geometry {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

TEST(CurveBasis, PartitionOfUnityAndNonNegativityAtRandomAbscissas) {
  // Σ b_i = 1: each b_i is computed with a relative error of a few ε and there are at most six
  // of them, all <= 1.07 in magnitude (Catmull-Rom peaks at 1): |Σ b_i − 1| <~ 6·4ε ≈ 5e-15,
  // inside the required 1e-14. Σ b'_i = Σ b''_i = 0 (derivatives of a constant), to round-off
  // relative to Σ|b'_i| (resp. Σ|b''_i|): 64ε of it.
  // B-spline values come from the Cox–de Boor products of non-negative factors
  // (u − t_i >= 0 and t_{i+r+1} − u >= 0 on the span), so they are >= 0 exactly in floating point.
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    BasisRow row;
    for (int k = 0; k < 1000; ++k) {
      const double s = k == 0 ? 0.0 : (k == 1 ? 1.0 : u(rng));
      basis->evaluate(s, row);
      double sum = 0.0, sum1 = 0.0, sum2 = 0.0, abs1 = 0.0, abs2 = 0.0;
      for (int j = 0; j < row.count; ++j) {
        sum += row.value[j];
        sum1 += row.d1[j];
        sum2 += row.d2[j];
        abs1 += std::abs(row.d1[j]);
        abs2 += std::abs(row.d2[j]);
        if (non_negative) {
          ASSERT_GE(row.value[j], 0.0) << "s = " << s << " j = " << j;
        }
      }
      ASSERT_NEAR(sum, 1.0, 1e-14) << "s = " << s;
      ASSERT_LE(std::abs(sum1), 64 * kEps * abs1) << "s = " << s;
      ASSERT_LE(std::abs(sum2), 64 * kEps * abs2) << "s = " << s;
    }
  }
}

TEST(CurveBasis, SupportIsExactlyDegreePlusOneConsecutiveFunctions) {
  // At every s exactly degree + 1 consecutive functions are reported, inside 0..n−1, and the
  // reported first index is the one the degree implies: ⌊N s⌋ for the uniform bases (N = n − 3
  // segments), span − d for NUBS. For NUBS, b_i must be > 0 strictly inside its support
  // (t_i, t_{i+d+1}) and is 0 outside (it is not reported there).
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    const int n = basis->controlPointCount(), d = basis->degree();
    std::mt19937 rng(11);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    BasisRow row;
    const auto* nubs = dynamic_cast<const NonUniformBSpline*>(basis.get());
    for (int k = 0; k < 1000; ++k) {
      const double s = u(rng);
      basis->evaluate(s, row);
      ASSERT_EQ(row.count, d + 1);
      ASSERT_GE(row.first, 0);
      ASSERT_LE(row.first + row.count, n);
      if (nubs) {
        const double x = nubs->parameterAt(s);
        const std::vector<double>& t = nubs->knots();
        ASSERT_EQ(row.first, findKnotSpan(d, n, t, x) - d);
        for (int j = 0; j <= d; ++j) {
          const int i = row.first + j;
          ASSERT_LE(t[i], x);
          ASSERT_GE(t[i + d + 1], x);
          if (t[i] < x && x < t[i + d + 1]) {
            ASSERT_GT(row.value[j], 0.0) << "b_" << i << " at u = " << x;
          }
        }
      } else {
        ASSERT_EQ(row.first, std::min(static_cast<int>(std::floor(s * (n - 3))), n - 4));
      }
    }
  }
}

TEST(CurveBasis, GaussQuadraturePerPieceIsExactBetweenBreakpoints) {
  // If breakpoints() lists every place where a b_i stops being one polynomial, (d + 1)-point
  // Gauss-Legendre per piece integrates b_i b_j (degree 2d) exactly, and so does a 12-point rule
  // on each half piece: the two agree to round-off (sums of ~n·12 terms of size <= 1/n: 1e-14).
  // A missing breakpoint would leave a kink inside a piece and an O(1e-4) disagreement.
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    const std::vector<double> pieces = basis->breakpoints();
    ASSERT_GE(pieces.size(), 2u);
    EXPECT_EQ(pieces.front(), 0.0);
    EXPECT_EQ(pieces.back(), 1.0);
    for (std::size_t k = 0; k + 1 < pieces.size(); ++k) ASSERT_LT(pieces[k], pieces[k + 1]);
    const int n = basis->controlPointCount();
    auto gram = [&, &basis = basis](int nodes, int halves) {  // a structured binding is captured by name (clang 14)
      const QuadratureRule rule = gaussLegendre(nodes);
      MatX G = MatX::Zero(n, n);
      BasisRow row;
      for (std::size_t k = 0; k + 1 < pieces.size(); ++k)
        for (int h = 0; h < halves; ++h) {
          const double a = pieces[k] + (pieces[k + 1] - pieces[k]) * h / halves;
          const double b = pieces[k] + (pieces[k + 1] - pieces[k]) * (h + 1) / halves;
          for (std::size_t g = 0; g < rule.nodes.size(); ++g) {
            basis->evaluate(0.5 * (a + b) + 0.5 * (b - a) * rule.nodes[g], row);
            for (int i = 0; i < row.count; ++i)
              for (int j = 0; j < row.count; ++j)
                G(row.first + i, row.first + j) += 0.5 * (b - a) * rule.weights[g] * row.value[i] * row.value[j];
          }
        }
      return G;
    };
    EXPECT_LE((gram(basis->degree() + 1, 1) - gram(12, 2)).cwiseAbs().maxCoeff(), 1e-14);
  }
}

TEST(CurveBasis, DerivativesMatchCentralFiniteDifferences) {
  // Central difference (f(s+h) − f(s−h))/2h has truncation error <= h²/6 max|f'''| and
  // round-off <= e_f / h, with e_f the evaluation error of f. We divide by the exact distance of
  // the two rounded abscissas, and bound e_f by 16ε (M_f + M_f'): M_f for the arithmetic on
  // values of the row's size, M_f' for the rounding of the argument (u = t_d + s (t_n − t_d),
  // t = u − span, off by ~ε|u|, i.e. moving f by ~ε|f'|). M_k = the largest |b^(k)| of the row at
  // the three abscissas. We check b' against differences of b and b'' against differences of b',
  // away from breakpoints (f one polynomial on [s − h, s + h]). |f'''| is estimated from the
  // analytic b'' (|Δb''|/h, exact for cubic pieces) and for the check of b'' the fourth derivative
  // from its second difference; a factor 2 covers their variation over [s − h, s + h].
  const double h = 1e-5;
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    const std::vector<double> pieces = basis->breakpoints();
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    BasisRow minus, mid, plus;
    int checked = 0;
    for (int k = 0; k < 400; ++k) {
      const double s = u(rng);
      const bool near_break = std::any_of(pieces.begin(), pieces.end(), [&](double b) { return std::abs(b - s) <= 2 * h; });
      if (near_break) continue;
      const double sm = s - h, sp = s + h, step = sp - sm;  // step exact (Sterbenz)
      basis->evaluate(sm, minus);
      basis->evaluate(s, mid);
      basis->evaluate(sp, plus);
      ASSERT_EQ(minus.first, mid.first);
      ASSERT_EQ(plus.first, mid.first);
      double m0 = 0.0, m1 = 0.0, m2 = 0.0;
      for (const BasisRow* r : {&minus, &mid, &plus})
        for (int j = 0; j < r->count; ++j) {
          m0 = std::max(m0, std::abs(r->value[j]));
          m1 = std::max(m1, std::abs(r->d1[j]));
          m2 = std::max(m2, std::abs(r->d2[j]));
        }
      for (int j = 0; j < mid.count; ++j) {
        const double m3 = std::max(std::abs(plus.d2[j] - mid.d2[j]), std::abs(mid.d2[j] - minus.d2[j])) / h;
        const double m4 = std::abs(plus.d2[j] - 2 * mid.d2[j] + minus.d2[j]) / (h * h);
        const double fd1 = (plus.value[j] - minus.value[j]) / step;
        const double fd2 = (plus.d1[j] - minus.d1[j]) / step;
        EXPECT_NEAR(mid.d1[j], fd1, 2 * h * h / 6 * m3 + 16 * kEps * (m0 + m1) / h) << "b'_" << j << " at s = " << s;
        EXPECT_NEAR(mid.d2[j], fd2, 2 * h * h / 6 * m4 + 16 * kEps * (m1 + m2) / h) << "b''_" << j << " at s = " << s;
      }
      ++checked;
    }
    EXPECT_GT(checked, 100);
  }
}

TEST(CurveBasis, CurveDerivativesAreContinuousUpToTheAdvertisedOrder) {
  // For a C^k basis (k = continuity()), P^{(m)}, m <= min(k, 2), is continuous at every interior
  // breakpoint: its jump over [s_b − δ, s_b + δ] is at most 2δ max|P^{(m+1)}|, so it shrinks
  // linearly with δ. We check jump(δ) <= jump(δ₀) δ/δ₀ · 4 for δ = δ₀/10^j (linear decrease with a
  // margin for the variation of P^{(m+1)}), plus round-off of the evaluation (16ε |P^{(m)}|).
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    const int k = std::min(basis->continuity(), 2);
    if (k < 0) continue;
    std::mt19937 rng(17);
    const Points q = test::randomControlPoints(basis->controlPointCount(), rng);
    const std::vector<double> pieces = basis->breakpoints();
    for (std::size_t b = 1; b + 1 < pieces.size(); ++b) {
      const double sb = pieces[b];
      auto derivative = [&, &basis = basis](double s, int m) {  // binding captured by name (clang 14)
        const CurveDerivatives c = curveDerivatives(*basis, q, s);
        return m == 0 ? c.point : (m == 1 ? c.first : c.second);
      };
      for (int m = 0; m <= k; ++m) {
        const double d0 = 1e-3;
        const double gap = std::min(sb - pieces[b - 1], pieces[b + 1] - sb);
        if (d0 >= gap) continue;
        const double jump0 = (derivative(sb + d0, m) - derivative(sb - d0, m)).norm();
        const double scale = derivative(sb, m).norm();
        for (double delta : {1e-4, 1e-5, 1e-6, 1e-7}) {
          const double jump = (derivative(sb + delta, m) - derivative(sb - delta, m)).norm();
          EXPECT_LE(jump, 4 * jump0 * delta / d0 + 16 * kEps * scale + 1e-300)
              << "P^(" << m << ") at breakpoint s = " << sb << ", delta = " << delta;
        }
      }
    }
  }
}

TEST(CurveBasis, AbscissasOutsideTheUnitIntervalAreClamped) {
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    BasisRow inside, outside;
    basis->evaluate(0.0, inside);
    basis->evaluate(-0.5, outside);
    EXPECT_EQ(inside.first, outside.first);
    for (int j = 0; j < inside.count; ++j) EXPECT_EQ(inside.value[j], outside.value[j]);
    basis->evaluate(1.0, inside);
    basis->evaluate(3.0, outside);
    EXPECT_EQ(inside.first, outside.first);
    for (int j = 0; j < inside.count; ++j) EXPECT_EQ(inside.value[j], outside.value[j]);
  }
}

TEST(CurveBasis, CloneBehavesLikeTheOriginal) {
  for (const auto& [label, basis, non_negative] : test::allTestBases()) {
    SCOPED_TRACE(label);
    const auto copy = basis->clone();
    EXPECT_EQ(copy->name(), basis->name());
    EXPECT_EQ(copy->controlPointCount(), basis->controlPointCount());
    EXPECT_EQ(copy->breakpoints(), basis->breakpoints());
    BasisRow a, b;
    basis->evaluate(0.37, a);
    copy->evaluate(0.37, b);
    EXPECT_EQ(a.first, b.first);
    for (int j = 0; j < a.count; ++j) EXPECT_EQ(a.d2[j], b.d2[j]);
  }
}

}  // namespace
}  // namespace filum::geometry
