// Catenary: a thread of length L hanging under gravity between two fixed points a span S < L
// apart, at the same height, comes to rest on
//   z(x) = a cosh((x − S/2)/a) + c,   2 a sinh(S/(2a)) = L   (a from the length constraint),
// c such that z(0) = z(S) = 0. Exact for an inextensible string without bending stiffness;
// the model's thread is extensible: with the real suture (E A = 63 N, weight μ g = 2.8e-4 N/m)
// the largest tension w (a + sag) ≈ 1.7e-5 N stretches it by ε ≈ 3e-7, which moves the curve by
// O(L ε) ≈ 2e-8 m — the floor of the measured error. Above it, the discretization error of a
// stiff stretching penalty on a cubic spline: membrane locking while the knot spacing is coarse
// (|P'| cannot stay exactly L at every quadrature node of a curved cubic piece), then fast decay.
//
// Scene: a DynamicSpline of mass μL whose control points start on a circular arc of length L
// through both supports (uniform in arc length, so the rest parametrization is uniform; the
// second and last-but-one moved so that P(0) and P(1) sit exactly on the supports), a
// GreenLagrangeStretching with rest length L, no bending, viscous damping γ, FixedPointConstraint
// at s = 0 and s = 1. error(): the largest distance from P(s) (401 abscissas) to the analytic
// curve (m).
#pragma once

#include "validation/reference_problem.hpp"

namespace filum::validation {

class Catenary final : public ReferenceProblem {
 public:
  struct Options {
    double length = 0.1;     // L, rest length (m)
    double span = 0.08;      // S (m), < L
    Material material;       // E, r, ρ
    double damping = 30.0;   // γ (1/s), viscous: the slowest swing (≈ 18 rad/s) is near critical
    double duration = 2.0;   // s: the Baumgarte transient (1 + ωt) e^{−ωt} of the initial end offsets is ~1e-16 m by then
  };
  explicit Catenary(Options options);
  Catenary() : Catenary(Options{}) {}

  std::string name() const override { return "catenary"; }
  std::string errorMeaning() const override { return "max distance of P(s) to the analytic catenary at rest (m)"; }
  nlohmann::json scene(const RunSettings& settings) const override;
  double duration() const override { return options_.duration; }
  double error(const Scene& scene) const override;

  const Options& options() const { return options_; }
  /// a (m), from 2 a sinh(S / 2a) = L.
  double parameter() const { return a_; }
  /// z(x) of the analytic curve (m), z(0) = z(S) = 0.
  double height(double x) const;
  /// Distance from p to the analytic curve in the x-z plane (p_y counted as an offset), m.
  double distance(const Vec3& p) const;

 private:
  Options options_;
  double a_;
};

}  // namespace filum::validation
