#include "validation/catenary.hpp"

#include <cmath>
#include <stdexcept>

#include "filum/geometry/spline_curve.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::validation {

namespace {

/// Root u > 0 of sinh(u)/u = ratio (> 1), Newton from the series sinh u/u ≈ 1 + u²/6.
double sinhOverXRoot(double ratio) {
  double u = std::sqrt(6.0 * (ratio - 1.0));
  for (int k = 0; k < 100; ++k) {
    const double f = std::sinh(u) - ratio * u, df = std::cosh(u) - ratio;
    const double step = f / df;
    u -= step;
    if (std::abs(step) < 1e-15 * u) break;
  }
  return u;
}

/// Root Θ ∈ (0, π) of sin(Θ)/Θ = ratio (< 1).
double sinOverXRoot(double ratio) {
  double theta = std::sqrt(6.0 * (1.0 - ratio));
  for (int k = 0; k < 100; ++k) {
    const double f = std::sin(theta) - ratio * theta, df = std::cos(theta) - ratio;
    const double step = f / df;
    theta -= step;
    if (std::abs(step) < 1e-15 * theta) break;
  }
  return theta;
}

}  // namespace

Catenary::Catenary(Options options) : options_(options) {
  if (!(options_.span < options_.length)) throw std::invalid_argument("Catenary: the span must be shorter than the length");
  // 2a sinh(S/2a) = L  ⇔  sinh(u)/u = L/S with u = S/(2a).
  a_ = options_.span / (2.0 * sinhOverXRoot(options_.length / options_.span));
}

double Catenary::height(double x) const {
  const double S = options_.span;
  return a_ * (std::cosh((x - 0.5 * S) / a_) - std::cosh(0.5 * S / a_));
}

double Catenary::distance(const Vec3& p) const {
  // Closest point (x, z(x)) of the graph to (p_x, p_z). It lies within |x − p_x| <= d0, d0 the
  // vertical distance |z(p_x) − p_z| (a bound of the distance), so: golden-section search of
  // f(x) = (x − p_x)² + (z(x) − p_z)² on that interval (f is unimodal there while d0 is small
  // against the radius of curvature a; otherwise the result is still a distance <= d0), then
  // Newton on f'(x) = 0 for the last digits, each step kept only if it lowers f.
  const double S = options_.span;
  const auto f = [&](double x) {
    const double dx = x - p.x(), dz = height(x) - p.z();
    return dx * dx + dz * dz;
  };
  const double d0 = std::abs(height(p.x()) - p.z());
  double lo = p.x() - d0, hi = p.x() + d0;
  const double ratio = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = hi - ratio * (hi - lo), x2 = lo + ratio * (hi - lo), f1 = f(x1), f2 = f(x2);
  for (int k = 0; k < 200 && hi - lo > 1e-15 * (1.0 + std::abs(p.x())); ++k) {
    if (f1 < f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - ratio * (hi - lo);
      f1 = f(x1);
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + ratio * (hi - lo);
      f2 = f(x2);
    }
  }
  double x = 0.5 * (lo + hi), best = f(x);
  for (int k = 0; k < 5; ++k) {
    const double u = (x - 0.5 * S) / a_;
    const double z = height(x), dz = std::sinh(u), d2z = std::cosh(u) / a_;
    const double F = (x - p.x()) + (z - p.z()) * dz;
    const double dF = 1.0 + dz * dz + (z - p.z()) * d2z;
    const double candidate = x - F / dF;
    const double fc = f(candidate);
    if (!(fc < best)) break;
    x = candidate;
    best = fc;
  }
  return std::sqrt(best + p.y() * p.y());
}

nlohmann::json Catenary::scene(const RunSettings& settings) const {
  const double L = options_.length, S = options_.span;
  const int n = settings.control_points;
  // Initial control points on the circular arc of length L through (0,0,0) and (S,0,0),
  // q_i at arc length L (i − 1)/(n − 3) (the abscissas of a straight uniform B-spline thread).
  const double theta = sinOverXRoot(S / L), R = L / (2.0 * theta);
  Points q(n, 3);
  for (int i = 0; i < n; ++i) {
    const double phi = -theta + (L * (i - 1.0) / (n - 3)) / R;
    q.row(i) << 0.5 * S + R * std::sin(phi), 0.0, R * std::cos(theta) - R * std::cos(phi);
  }
  // The curve's ends P(0) = (q0 + 4 q1 + q2)/6 and P(1) = (q_{n−3} + 4 q_{n−2} + q_{n−1})/6 put
  // exactly on the supports (the arc's control polygon alone misses them by O(h² / R)).
  q.row(1) = -(q.row(0) + q.row(2)) / 4.0;
  q.row(n - 2) = (6.0 * Eigen::RowVector3d(S, 0.0, 0.0) - q.row(n - 3) - q.row(n - 1)) / 4.0;
  nlohmann::json points = nlohmann::json::array();
  for (int i = 0; i < n; ++i) points.push_back({q(i, 0), q(i, 1), q(i, 2)});
  const Material& m = options_.material;
  nlohmann::json components = nlohmann::json::array();
  components.push_back(splineComponent(points, m.linearDensity() * L, m.radius));
  components.push_back({{"type", "GreenLagrangeStretching"}, {"youngs_modulus", m.youngs_modulus}, {"rest_length", L}});
  components.push_back({{"type", "ViscousDamping"}, {"coefficient", options_.damping}});
  components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 0.0}, {"target", {0.0, 0.0, 0.0}}});
  components.push_back({{"type", "FixedPointConstraint"}, {"abscissa", 1.0}, {"target", {S, 0.0, 0.0}}});
  return {{"name", "catenary"},
          {"dt", settings.dt},
          {"duration", options_.duration},
          {"gravity", {0.0, 0.0, -9.81}},
          {"integrator", settings.integrator},
          {"nodes", nlohmann::json::array({{{"name", "thread"}, {"components", components}}})}};
}

double Catenary::error(const Scene& scene) const {
  const CurveBody& spline = *scene.bodies().front()->curve();  // a spline: built above
  const Points curve = geometry::sampleCurve(spline.basis(), spline.block(scene.state().q), 401);
  double worst = 0.0;
  for (int k = 0; k < curve.rows(); ++k) worst = std::max(worst, distance(curve.row(k).transpose()));
  return worst;
}

}  // namespace filum::validation
