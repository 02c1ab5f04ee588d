// Baumgarte stabilization (J. Baumgarte, 1972) of a position constraint g(q, t) = 0 solved at
// the acceleration level (paper §4, [Lenoir talk 2008] "Lagrange multipliers + Baumgarte scheme"):
//   g̈ = −2ω ġ − ω² g,
// the critically damped choice (both roots at −ω): a violation left by the integrator decays
// like (1 + ω t) e^{−ω t} instead of drifting. ω = 0 keeps only g̈ = 0 (drift grows).
#pragma once

#include <optional>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum {
class Scene;
}

namespace filum::constraints {

class Baumgarte {
 public:
  /// omega: ω (1/s) >= 0; nullopt: one tenth of 1/dt, resolved by init().
  explicit Baumgarte(std::optional<double> omega = std::nullopt) : omega_(omega) {}
  /// "stabilization": ω (1/s, >= 0, default 0.1/dt).
  static Baumgarte fromParams(const Params& p);
  /// Resolves the default ω = 0.1/dt (ω dt = 0.1: well inside every explicit scheme's stability
  /// region, and fast enough that the integrator's O(dt^{p+1}) local error is pulled back at
  /// once).
  void init(const Scene& scene);

  double omega() const { return omega_.value_or(0.0); }
  /// The stabilizing acceleration −2ω ġ − ω² g (same shape as g).
  template <class V>
  V term(const V& g, const V& dg) const {
    const double w = omega();
    return -2.0 * w * dg - w * w * g;
  }
  double term(double g, double dg) const {
    const double w = omega();
    return -2.0 * w * dg - w * w * g;
  }

 private:
  std::optional<double> omega_;
};

}  // namespace filum::constraints
