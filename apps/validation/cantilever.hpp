// Cantilever under its own weight (Euler-Bernoulli beam, small deflection): a thread of length L
// clamped at x = 0 along x, free at x = L, loaded by its weight q = μ g per unit length:
//   static tip deflection   δ = q L⁴ / (8 E I),
//   static deflection       w_s(x) = q x² (6L² − 4L x + x²) / (24 E I),
// and, released from the straight shape at rest with gravity switched on at t = 0 (undamped),
//   w(L, t) = Σ_k c_k φ_k(L) (1 − cos ω_k t),   ω_k = (λ_k/L)² √(EI/μ),   c_k = ⟨w_s, φ_k⟩/⟨φ_k, φ_k⟩,
// with cos λ_k cosh λ_k = −1 (λ_1 = 1.8751) and the clamped-free modes
//   φ_k(x) = cosh z − cos z − σ_k (sinh z − sin z),  z = λ_k x/L,
//   σ_k = (cosh λ_k + cos λ_k)/(sinh λ_k + sin λ_k)   (20 modes: c_k φ_k(L) ~ k⁻⁵, truncation < 1e-6 δ).
// Valid while δ ≪ L (geometric nonlinearity enters at O((qL³/EI)²) relative).
//
// Scene: a straight DynamicSpline from (0,0,0) to (L,0,0) of mass μL, GreenLagrangeStretching,
// a bending energy ("ParametricBending" or "CurvatureBending"), a ClampConstraint at s = 0
// (position and tangent), optional viscous damping γ. error(): |w_tip(t) − w(L, t)| / δ, the
// largest over samples every T_1/40 (T_1 = 2π/ω_1) for one period of the first mode.
#pragma once

#include <string>
#include <vector>

#include "validation/reference_problem.hpp"

namespace filum::validation {

class Cantilever final : public ReferenceProblem {
 public:
  struct Options {
    double length = 0.03;  // L (m): δ/L ≈ 0.6 % for a 3-0 polypropylene suture
    Material material;
    std::string bending = "ParametricBending";
    double damping = 0.0;   // viscous γ (1/s); the dynamic solution assumes 0
    double periods = 1.0;   // run length in periods of mode 1
    int modes = 20;         // modes of the analytic series
  };
  explicit Cantilever(Options options);
  Cantilever() : Cantilever(Options{}) {}

  std::string name() const override { return "cantilever"; }
  std::string errorMeaning() const override { return "max |w_tip - w_tip_exact| / static tip deflection over one period"; }
  nlohmann::json scene(const RunSettings& settings) const override;
  double duration() const override { return options_.periods * 2.0 * 3.14159265358979323846 / omega(0); }
  std::vector<double> sampleTimes() const override;
  double error(const Scene& scene) const override;

  const Options& options() const { return options_; }
  /// q = μ g (N/m).
  double load() const;
  /// δ = q L⁴ / (8 E I) (m), downward.
  double staticTipDeflection() const;
  /// w(L, t) of the undamped release (m, downward), modal series.
  double tipDeflection(double t) const;
  /// ω_k (rad/s), k from 0.
  double omega(int k) const { return omega_[k]; }
  /// The model's tip deflection: −z of P(1) (m).
  static double modelTipDeflection(const Scene& scene);

 private:
  Options options_;
  std::vector<double> omega_, tip_amplitude_;  // ω_k, c_k φ_k(L)
};

}  // namespace filum::validation
