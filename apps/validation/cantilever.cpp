#include "validation/cantilever.hpp"

#include <cmath>
#include <numbers>

#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::validation {

namespace {

constexpr double kGravity = 9.81;

/// λ_k: root of cos λ cosh λ = −1 near (2k + 1) π/2 (k from 0), Newton on the scaled
/// g(λ) = cos λ + 1/cosh λ.
double clampedFreeRoot(int k) {
  double x = k == 0 ? 1.8751 : (2.0 * k + 1.0) * std::numbers::pi / 2.0;
  for (int i = 0; i < 100; ++i) {
    const double g = std::cos(x) + 1.0 / std::cosh(x);
    const double dg = -std::sin(x) - std::sinh(x) / (std::cosh(x) * std::cosh(x));
    const double step = g / dg;
    x -= step;
    if (std::abs(step) < 1e-15 * x) break;
  }
  return x;
}

/// φ(z) = cosh z − cos z − σ (sinh z − sin z), evaluated without cancellation for large λ:
/// cosh z − σ sinh z = ½ [(1 − σ) e^z + (1 + σ) e^−z], 1 − σ = (sin λ − cos λ − e^−λ)/(sinh λ + sin λ).
double modeShape(double lambda, double z) {
  const double denominator = std::sinh(lambda) + std::sin(lambda);
  const double one_minus_sigma = (std::sin(lambda) - std::cos(lambda) - std::exp(-lambda)) / denominator;
  const double sigma = 1.0 - one_minus_sigma;
  return 0.5 * one_minus_sigma * std::exp(z) + 0.5 * (1.0 + sigma) * std::exp(-z) - std::cos(z) + sigma * std::sin(z);
}

}  // namespace

Cantilever::Cantilever(Options options) : options_(options) {
  const Material& m = options_.material;
  const double L = options_.length, EI = m.bendingStiffness(), q = load();
  const geometry::QuadratureRule rule = geometry::gaussLegendre(16);
  const int pieces = 40;
  for (int k = 0; k < options_.modes; ++k) {
    const double lambda = clampedFreeRoot(k);
    omega_.push_back(lambda * lambda / (L * L) * std::sqrt(EI / m.linearDensity()));
    // c_k = ⟨w_s, φ_k⟩ / ⟨φ_k, φ_k⟩ by Gauss-Legendre on 40 pieces of [0, L].
    double num = 0.0, den = 0.0;
    for (int p = 0; p < pieces; ++p) {
      const double a = L * p / pieces, b = L * (p + 1) / pieces;
      num += geometry::integrate(rule, a, b, [&](double x) {
        const double ws = q * x * x * (6 * L * L - 4 * L * x + x * x) / (24.0 * EI);
        return ws * modeShape(lambda, lambda * x / L);
      });
      den += geometry::integrate(rule, a, b, [&](double x) {
        const double phi = modeShape(lambda, lambda * x / L);
        return phi * phi;
      });
    }
    tip_amplitude_.push_back(num / den * modeShape(lambda, lambda));
  }
}

double Cantilever::load() const { return options_.material.linearDensity() * kGravity; }

double Cantilever::staticTipDeflection() const {
  return load() * std::pow(options_.length, 4) / (8.0 * options_.material.bendingStiffness());
}

double Cantilever::tipDeflection(double t) const {
  double w = 0.0;
  for (std::size_t k = 0; k < omega_.size(); ++k) w += tip_amplitude_[k] * (1.0 - std::cos(omega_[k] * t));
  return w;
}

double Cantilever::modelTipDeflection(const Scene& scene) {
  const CurveBody& spline = *scene.bodies().front()->curve();  // a spline: built above
  return -geometry::curvePoint(spline.basis(), spline.block(scene.state().q), 1.0).z();
}

nlohmann::json Cantilever::scene(const RunSettings& settings) const {
  const double L = options_.length;
  const Material& m = options_.material;
  nlohmann::json components = nlohmann::json::array();
  components.push_back(splineComponent(
      {{"from", {0.0, 0.0, 0.0}}, {"to", {L, 0.0, 0.0}}, {"count", settings.control_points}}, m.linearDensity() * L,
      m.radius));
  components.push_back({{"type", "GreenLagrangeStretching"}, {"youngs_modulus", m.youngs_modulus}});
  components.push_back({{"type", options_.bending}, {"youngs_modulus", m.youngs_modulus}});
  if (options_.damping > 0.0) components.push_back({{"type", "ViscousDamping"}, {"coefficient", options_.damping}});
  components.push_back({{"type", "ClampConstraint"}, {"abscissa", 0.0}});
  return {{"name", "cantilever"},
          {"dt", settings.dt},
          {"duration", duration()},
          {"gravity", {0.0, 0.0, -kGravity}},
          {"integrator", settings.integrator},
          {"nodes", nlohmann::json::array({{{"name", "beam"}, {"components", components}}})}};
}

std::vector<double> Cantilever::sampleTimes() const {
  const double period = 2.0 * std::numbers::pi / omega(0);
  std::vector<double> times;
  const int count = static_cast<int>(std::lround(40.0 * options_.periods));
  for (int i = 1; i <= count; ++i) times.push_back(i * period / 40.0);
  return times;
}

double Cantilever::error(const Scene& scene) const {
  return std::abs(modelTipDeflection(scene) - tipDeflection(scene.state().time)) / staticTipDeflection();
}

}  // namespace filum::validation
