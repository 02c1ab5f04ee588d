// The dynamic spline on every basis geometry/ has: Catmull-Rom (C1, interpolating) and
// NUBS of degree 2 to 5, besides the uniform cubic B-spline. Checked against their definitions
// and against physics:
//  - the mass matrix M_ij = m ∫ b_i b_j ds (exact Gauss per piece in the code) against composite
//    Simpson quadrature of the same integral, an independent rule;
//  - the Green–Lagrange stretching energy of a uniformly stretched straight thread against its
//    closed form ½ E A ε² L₀, ε = (λ² − 1)/2 (any basis reproduces the straight thread exactly);
//  - the catenary (apps/validation/catenary.hpp): a suture hanging between two points comes to
//    rest on the analytic curve, within a bound that shrinks with n at the basis's order, under
//    implicit Euler (NUBS of degree 3 and 4; see the test for the others).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "filum/all_components.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/geometry/knot_vector.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/mass_matrix.hpp"
#include "validation/catenary.hpp"

namespace filum {
namespace {

using nlohmann::json;

/// The DynamicSpline component of a straight 10 cm thread on `basis` (a JSON object merged in).
json straightThread(const json& basis, int n) {
  json c = {{"type", "DynamicSpline"}, {"control_points", {{"from", {0, 0, 0}}, {"to", {0.1, 0, 0}}, {"count", n}}},
            {"radius", 1e-4}, {"density", 910}};
  for (const auto& [key, value] : basis.items()) c[key] = value;
  return c;
}

std::unique_ptr<Scene> threadScene(const json& spline, const json& extra = json::array()) {
  json components = json::array({spline});
  for (const auto& c : extra) components.push_back(c);
  const json doc = {{"name", "bases"}, {"dt", 1e-3}, {"duration", 1.0}, {"gravity", {0, 0, 0}},
                    {"integrator", {{"type", "ImplicitEuler"}}},
                    {"nodes", json::array({{{"name", "thread"}, {"components", components}}})}};
  return loadScene(doc, "spline bases test", app::makeFactory());
}

const json kBases[] = {{{"basis", "catmull_rom"}},
                       {{"basis", "nubs"}, {"degree", 2}},
                       {{"basis", "nubs"}, {"degree", 3}},
                       {{"basis", "nubs"}, {"degree", 4}},
                       {{"basis", "nubs"}, {"degree", 5}},
                       {{"basis", "nubs"}, {"degree", 4}, {"clamped", false}},
                       {{"basis", "nubs"}, {"degree", 3},
                        {"knots", {0, 0, 0, 0, 0.05, 0.2, 0.22, 0.5, 0.51, 0.52, 0.8, 1, 1, 1, 1}}}};

TEST(SplineBases, MassMatrixAgainstSimpsonQuadrature) {
  for (const json& basis : kBases) {
    const int n = basis.contains("knots") ? 11 : 12;
    auto scene = threadScene(straightThread(basis, n));
    const auto& spline = dynamic_cast<const mechanics::DynamicSpline&>(*scene->bodies().front());
    const double m = spline.mass();
    const SparseMatrix M = mechanics::massMatrix(spline.basis(), m);
    // Composite Simpson on every polynomial piece, 1000 panels each: its error on a polynomial of
    // degree 2d <= 10 over a piece of width w is w⁵ max|f⁽⁴⁾| / (180 · 1000⁴); with f⁽⁴⁾ of order
    // f (2d)⁴ / w⁴ that is 1e-14 of the entries (a piece's products have 2d <= 10 powers of 1/w).
    MatX simpson = MatX::Zero(n, n);
    const std::vector<double> pieces = spline.basis().breakpoints();
    geometry::BasisRow row;
    for (std::size_t p = 0; p + 1 < pieces.size(); ++p) {
      const int panels = 1000;
      const double a = pieces[p], w = (pieces[p + 1] - a) / panels;
      for (int k = 0; k <= 2 * panels; ++k) {
        const double s = a + 0.5 * w * k;
        const double weight = (k == 0 || k == 2 * panels ? 1.0 : k % 2 ? 4.0 : 2.0) * w / 6.0;
        // Inside the piece (its own polynomial at the ends: from the right at a, the left at b).
        if (k == 2 * panels)
          spline.basis().evaluateFromLeft(s, row);
        else
          spline.basis().evaluate(s, row);
        for (int i = 0; i < row.count; ++i)
          for (int j = 0; j < row.count; ++j)
            simpson(row.first + i, row.first + j) += weight * m * row.value[i] * row.value[j];
      }
    }
    const MatX exact = MatX(M);
    EXPECT_LT((exact - simpson).cwiseAbs().maxCoeff(), 1e-10 * exact.cwiseAbs().maxCoeff()) << basis.dump();
  }
}

TEST(SplineBases, StretchingEnergyOfAUniformStretch) {
  // Every control point carried to λ x along the thread's axis: P' = λ P0' everywhere, and
  // E = ½ ∫ E A ε² dσ = ½ E A ((λ² − 1)/2)² L₀ exactly; the quadrature of each piece is exact
  // for this polynomial (green_lagrange_stretching.hpp), so only round-off separates them.
  const double E = 2e9, A = M_PI * 1e-8, L = 0.1, lambda = 1.01;
  for (const json& basis : kBases) {
    const int n = basis.contains("knots") ? 11 : 12;
    auto scene = threadScene(straightThread(basis, n), json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", E}}}));
    SceneState s = scene->state();
    for (int i = 0; i < n; ++i) s.q[3 * i] *= lambda;
    const double epsilon = (lambda * lambda - 1.0) / 2.0;
    const double expected = 0.5 * E * A * epsilon * epsilon * L;
    EXPECT_NEAR(scene->energy(s).potential, expected, 1e-12 * expected) << basis.dump();
  }
}

TEST(SplineBases, TheCatenaryOnNubsOfDegreeThreeAndFour) {
  const validation::Catenary problem;
  validation::RunSettings settings;
  settings.dt = 5e-3;
  const double L = problem.options().length, S = problem.options().span;
  const double theta = [&] {  // the circular arc of length L through the supports: sin θ / θ = S / L
    double t = 1.0;
    for (int it = 0; it < 100; ++it) t -= (std::sin(t) / t - S / L) / ((t * std::cos(t) - std::sin(t)) / (t * t));
    return t;
  }();
  const double R = L / (2.0 * theta);
  auto arc = [&](double sigma) {  // the point at arc length σ L
    const double phi = -theta + sigma * L / R;
    return Vec3(0.5 * S + R * std::sin(phi), 0.0, R * std::cos(theta) - R * std::cos(phi));
  };
  // NUBS of degree 3 and 4. (Degree 2, degree 5 and Catmull-Rom lock under the stiff
  // stretching energy at these n — 5.7e-4, 1.7e-4 and 6.3e-4 m at n = 40, against 2.1e-5 and
  // 2.8e-7 m for degrees 3 and 4 —: the exact |P'| at their Gauss nodes over-constrains a curved
  // piece; docs/writing-a-scene.md says to use degree 3 or 4 for stiff threads.)
  for (const json& basis : {kBases[2], kBases[3]}) {
    std::map<int, double> error;
    for (int n : {20, 40}) {
      settings.control_points = n;
      json doc = problem.scene(settings);
      json& spline = doc["nodes"][0]["components"][0];
      for (const auto& [key, value] : basis.items()) spline[key] = value;
      // Initial control points on the arc: at the Greville abscissae for a NUBS (its ends are
      // the first and last points), at (i − 1)/(n − 3) for Catmull-Rom (it passes through q_1 and
      // q_{n−2} at the ends).
      json points = json::array();
      if (basis["basis"] == "nubs") {
        const int d = basis["degree"];
        const geometry::NonUniformBSpline b(d, geometry::clampedUniformKnots(d, n));
        for (int i = 0; i < n; ++i) {
          double xi = 0.0;
          for (int k = 1; k <= d; ++k) xi += b.knots()[i + k];
          const Vec3 x = arc((xi / d - b.domainStart()) / (b.domainEnd() - b.domainStart()));
          points.push_back({x.x(), x.y(), x.z()});
        }
      } else {
        for (int i = 0; i < n; ++i) {
          const Vec3 x = arc((i - 1.0) / (n - 3));
          points.push_back({x.x(), x.y(), x.z()});
        }
      }
      spline["control_points"] = points;
      auto scene = loadScene(doc, "catenary", app::makeFactory());
      problem.prepare(*scene);
      std::string failure;
      ASSERT_TRUE(validation::advance(*scene, problem.duration(), &failure)) << basis.dump() << " n = " << n << ": " << failure;
      error[n] = problem.error(*scene);
      std::printf("  %s n = %d: max distance %.3e m\n", basis.dump().c_str(), n, error[n]);
      EXPECT_LT(scene->energy(scene->state()).kinetic, 1e-20) << basis.dump() << " n = " << n << " is not at rest";
    }
    // A spline of degree d >= 3 approximates the curve to O(h⁴) at least: halving h divides the
    // error by 2⁴ or more (measured 22 for degree 3, 240 for degree 4), down to the floor of the
    // thread's extensibility, L ε ≈ 2e-8 m (catenary_validation_test.cpp).
    EXPECT_GE(error[20] / error[40], 16.0) << basis.dump();
    EXPECT_LT(error[40], 1e-4) << basis.dump();  // 0.1 % of the length
  }
}

}  // namespace
}  // namespace filum
