// Taut string: a thread of rest length L0 held at both ends a span S > L0 apart carries the
// tension T (the Green-Lagrange stretching gives T = E A ε S/L0, ε = (S² − L0²)/(2 L0²)) and its
// small transverse vibrations have the frequencies
//   f_k = k/(2S) √(T/μ),   μ = m / S   (the thread's mass over its stretched length),
// and, started from rest in the shape of mode k with amplitude A ≪ S,
//   y(x, t) = A sin(kπ x/S) cos(2π f_k t).
//
// Scene: a straight DynamicSpline from (0,0,0) to (S,0,0), mass ρ A L0, GreenLagrangeStretching
// with rest length L0, no gravity, no damping, no bending, FixedPointConstraint at s = 0 and 1.
// prepare() sets the y coordinates of the control points to the L2 projection of the mode shape
// onto the spline space under the end conditions P_y(0) = P_y(1) = 0. error(): max over 101
// abscissas of |P_y(s, t) − y(S s, t)| / A, evaluated every T_k/20 over `periods` periods.
#pragma once

#include "validation/reference_problem.hpp"

namespace filum::validation {

class TautString final : public ReferenceProblem {
 public:
  struct Options {
    double span = 0.1;          // S (m)
    double prestrain = 0.01;    // S/L0 − 1
    Material material;
    int mode = 1;               // k
    double amplitude = 1e-6;    // A (m): A/S = 1e-5; the tension then changes by ~(πA/S)² EA/4 ≈ 2e-8 T, a frequency shift of 1e-8
    double periods = 2.0;       // run length in periods of mode k
  };
  explicit TautString(Options options) : options_(options) {}
  TautString() : TautString(Options{}) {}

  std::string name() const override { return "taut_string"; }
  std::string errorMeaning() const override {
    return "max |y - y_exact| / amplitude over the string and the run (mode " + std::to_string(options_.mode) + ")";
  }
  nlohmann::json scene(const RunSettings& settings) const override;
  void prepare(Scene& scene) const override;
  double duration() const override { return options_.periods / frequency(options_.mode); }
  std::vector<double> sampleTimes() const override;
  double error(const Scene& scene) const override;

  const Options& options() const { return options_; }
  double restLength() const { return options_.span / (1.0 + options_.prestrain); }
  double mass() const { return options_.material.linearDensity() * restLength(); }
  /// T = E A ε S / L0 (N).
  double tension() const;
  /// f_k = k/(2S) √(T/μ) with μ = m/S (Hz), for a tension T (default: tension()).
  double frequency(int k, double T = 0.0) const;

 private:
  Options options_;
};

}  // namespace filum::validation
