#include "filum/visual/radius_profile.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "filum/core/scene_error.hpp"

namespace filum::visual {

RadiusProfile::RadiusProfile(double radius) : u_{0.0}, r_{radius}, m_{0.0} {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("radius must be a positive finite number, got " + std::to_string(radius));
}

RadiusProfile::RadiusProfile(std::vector<double> u, std::vector<double> r) : u_(std::move(u)), r_(std::move(r)) {
  const std::size_t n = u_.size();
  if (n == 0 || r_.size() != n) throw std::invalid_argument("radius profile: need as many radii as abscissas, at least one");
  for (std::size_t i = 0; i < n; ++i) {
    if (!(u_[i] >= 0.0 && u_[i] <= 1.0))
      throw std::invalid_argument("radius profile entry " + std::to_string(i) + ": u must be in [0, 1], got " +
                                  std::to_string(u_[i]));
    if (i > 0 && !(u_[i] > u_[i - 1]))
      throw std::invalid_argument("radius profile entry " + std::to_string(i) + ": u must increase strictly");
    if (!(r_[i] > 0.0) || !std::isfinite(r_[i]))
      throw std::invalid_argument("radius profile entry " + std::to_string(i) + ": radius must be positive, got " +
                                  std::to_string(r_[i]));
  }
  // Fritsch–Carlson slopes: secants δ_i, initial slopes the mean of neighbouring secants (0 at
  // a local extremum), then limited so that α² + β² <= 9 on every interval (monotone).
  m_.assign(n, 0.0);
  if (n == 1) return;
  std::vector<double> delta(n - 1);
  for (std::size_t i = 0; i + 1 < n; ++i) delta[i] = (r_[i + 1] - r_[i]) / (u_[i + 1] - u_[i]);
  m_[0] = delta[0];
  m_[n - 1] = delta[n - 2];
  for (std::size_t i = 1; i + 1 < n; ++i) m_[i] = delta[i - 1] * delta[i] <= 0.0 ? 0.0 : 0.5 * (delta[i - 1] + delta[i]);
  for (std::size_t i = 0; i + 1 < n; ++i) {
    if (delta[i] == 0.0) {
      m_[i] = m_[i + 1] = 0.0;
      continue;
    }
    const double alpha = m_[i] / delta[i], beta = m_[i + 1] / delta[i];
    const double s = alpha * alpha + beta * beta;
    if (s > 9.0) {
      const double tau = 3.0 / std::sqrt(s);
      m_[i] = tau * alpha * delta[i];
      m_[i + 1] = tau * beta * delta[i];
    }
  }
}

RadiusProfile RadiusProfile::fromParams(const Params& p, double fallback) {
  if (p.has("radius_profile")) {
    if (p.has({"radius", "m"})) p.fail("radius", "either \"radius\" or \"radius_profile\", not both", "both");
    const nlohmann::json& list = p.raw({"radius_profile", "1, m"});
    if (!list.is_array() || list.empty())
      p.fail("radius_profile", "a non-empty list of [u, radius] pairs (u: fraction of the rest length in [0, 1], radius in m)",
             describeJson(list));
    std::vector<double> u, r;
    for (std::size_t i = 0; i < list.size(); ++i) {
      const nlohmann::json& e = list[i];
      if (!e.is_array() || e.size() != 2 || !e[0].is_number() || !e[1].is_number())
        p.fail("radius_profile", "[u, radius] pairs of numbers", "entry " + std::to_string(i) + " = " + describeJson(e));
      u.push_back(e[0].get<double>());
      r.push_back(e[1].get<double>());
    }
    try {
      return RadiusProfile(std::move(u), std::move(r));
    } catch (const std::invalid_argument& e) {
      p.fail("radius_profile", "u strictly increasing in [0, 1] and radii > 0", e.what());
    }
  }
  return RadiusProfile(p.positive({"radius", "m"}, fallback));
}

int RadiusProfile::interval(double u) const {
  const auto it = std::upper_bound(u_.begin(), u_.end(), u);
  return std::clamp(static_cast<int>(it - u_.begin()) - 1, 0, static_cast<int>(u_.size()) - 2);
}

double RadiusProfile::radius(double u) const {
  if (u_.size() == 1 || u <= u_.front()) return r_.front();
  if (u >= u_.back()) return r_.back();
  const int i = interval(u);
  const double h = u_[i + 1] - u_[i], t = (u - u_[i]) / h;
  const double t2 = t * t, t3 = t2 * t;
  return (2 * t3 - 3 * t2 + 1) * r_[i] + (t3 - 2 * t2 + t) * h * m_[i] + (-2 * t3 + 3 * t2) * r_[i + 1] +
         (t3 - t2) * h * m_[i + 1];
}

double RadiusProfile::slope(double u) const {
  if (u_.size() == 1 || u <= u_.front() || u >= u_.back()) return 0.0;
  const int i = interval(u);
  const double h = u_[i + 1] - u_[i], t = (u - u_[i]) / h;
  const double t2 = t * t;
  return ((6 * t2 - 6 * t) * r_[i] + (-6 * t2 + 6 * t) * r_[i + 1]) / h + (3 * t2 - 4 * t + 1) * m_[i] +
         (3 * t2 - 2 * t) * m_[i + 1];
}

double RadiusProfile::maxRadius() const { return *std::max_element(r_.begin(), r_.end()); }

}  // namespace filum::visual
