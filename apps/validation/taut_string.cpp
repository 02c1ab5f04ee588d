#include "validation/taut_string.hpp"

#include <cmath>
#include <numbers>

#include <Eigen/Dense>

#include "filum/geometry/gauss_legendre.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/mass_matrix.hpp"

namespace filum::validation {

double TautString::tension() const {
  const double S = options_.span, L0 = restLength();
  const double strain = (S * S - L0 * L0) / (2.0 * L0 * L0);  // Green-Lagrange ε
  return options_.material.axialStiffness() * strain * S / L0;
}

double TautString::frequency(int k, double T) const {
  if (T <= 0.0) T = tension();
  const double S = options_.span, mu = mass() / S;
  return k / (2.0 * S) * std::sqrt(T / mu);
}

nlohmann::json TautString::scene(const RunSettings& settings) const {
  const double S = options_.span;
  const Material& m = options_.material;
  nlohmann::json components = nlohmann::json::array();
  components.push_back(splineComponent(
      {{"from", {0.0, 0.0, 0.0}}, {"to", {S, 0.0, 0.0}}, {"count", settings.control_points}}, mass(), m.radius));
  components.push_back(
      {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", m.youngs_modulus}, {"rest_length", restLength()}});
  components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}});
  components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 1.0}});
  return {{"name", "taut string"},
          {"dt", settings.dt},
          {"duration", duration()},
          {"gravity", {0.0, 0.0, 0.0}},
          {"integrator", settings.integrator},
          {"nodes", nlohmann::json::array({{{"name", "string"}, {"components", components}}})}};
}

void TautString::prepare(Scene& scene) const {
  // Constrained L2 projection of A sin(kπ s) (s = x/S on the uniform straight thread):
  //   [G Lᵀ; L 0] [y; λ] = [r; 0],  G_ij = ∫ b_i b_j ds,  r_i = ∫ b_i A sin(kπ s) ds,
  // L the basis rows at s = 0 and s = 1 (the fixed ends).
  const CurveBody& spline = *scene.bodies().front()->curve();  // a spline: built above
  const CurveBasis& basis = spline.basis();
  const int n = spline.pointCount();
  MatX kkt = MatX::Zero(n + 2, n + 2);
  kkt.topLeftCorner(n, n) = MatX(mechanics::massMatrix(basis, 1.0));
  VecX rhs = VecX::Zero(n + 2);
  const geometry::QuadratureRule rule = geometry::gaussLegendre(10);
  const std::vector<double> pieces = basis.breakpoints();
  geometry::BasisRow row;
  const double k = options_.mode, A = options_.amplitude;
  for (std::size_t p = 0; p + 1 < pieces.size(); ++p) {
    const double half = 0.5 * (pieces[p + 1] - pieces[p]), mid = 0.5 * (pieces[p + 1] + pieces[p]);
    for (std::size_t g = 0; g < rule.nodes.size(); ++g) {
      const double s = mid + half * rule.nodes[g];
      basis.evaluate(s, row);
      for (int j = 0; j < row.count; ++j)
        rhs[row.first + j] += half * rule.weights[g] * row.value[j] * A * std::sin(k * std::numbers::pi * s);
    }
  }
  for (int e = 0; e < 2; ++e) {
    basis.evaluate(e == 0 ? 0.0 : 1.0, row);
    for (int j = 0; j < row.count; ++j) {
      kkt(n + e, row.first + j) = row.value[j];
      kkt(row.first + j, n + e) = row.value[j];
    }
  }
  const VecX y = kkt.fullPivLu().solve(rhs);
  SceneState state = scene.state();
  PointsMap q = spline.block(state.q);
  for (int i = 0; i < n; ++i) q(i, 1) = y[i];
  scene.setState(state);
}

std::vector<double> TautString::sampleTimes() const {
  const double period = 1.0 / frequency(options_.mode);
  std::vector<double> times;
  const int count = static_cast<int>(std::lround(20.0 * options_.periods));
  for (int i = 1; i <= count; ++i) times.push_back(i * period / 20.0);
  return times;
}

double TautString::error(const Scene& scene) const {
  const CurveBody& spline = *scene.bodies().front()->curve();  // a spline: built above
  const Points curve = geometry::sampleCurve(spline.basis(), spline.block(scene.state().q), 101);
  const double k = options_.mode, A = options_.amplitude;
  const double envelope = A * std::cos(2.0 * std::numbers::pi * frequency(options_.mode) * scene.state().time);
  double worst = 0.0;
  for (int j = 0; j < curve.rows(); ++j) {
    const double s = static_cast<double>(j) / (curve.rows() - 1);
    worst = std::max(worst, std::abs(curve(j, 1) - envelope * std::sin(k * std::numbers::pi * s)));
  }
  return worst / A;
}

}  // namespace filum::validation
