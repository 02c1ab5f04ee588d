// ElasticParameters: what every continuous elastic energy of a thread reads from its scene
// parameters, in SI units, and the cross-section of a round thread of radius r (the body's
// DynamicSpline::radius()): area A = π r² (stretching, E·A in N) and second moment of area
// I = π r⁴ / 4 (bending, E·I in N·m²). A 3-0 polypropylene suture: E ≈ 2 GPa, r = 1e-4 m.
#pragma once

#include <numbers>
#include <optional>

#include "filum/core/body_component.hpp"
#include "filum/core/params.hpp"

namespace filum::mechanics {

class DynamicSpline;

struct ElasticParameters {
  double youngs_modulus = 0.0;        // E (Pa) > 0
  std::optional<double> rest_length;  // ℓ0 (m) > 0; default: the initial curve (CurveQuadrature)
  int quadrature_nodes = 0;           // Gauss nodes per polynomial piece; 0: the energy's default

  /// "youngs_modulus": Pa (required), "rest_length": m (optional), "quadrature_nodes": k >= 1.
  static ElasticParameters fromParams(const Params& p);
};

inline double crossSectionArea(double radius) { return std::numbers::pi * radius * radius; }
inline double secondMomentOfArea(double radius) { return 0.25 * std::numbers::pi * radius * radius * radius * radius; }

/// The DynamicSpline a component acts on; throws SceneError naming the component otherwise.
const DynamicSpline& splineBody(const BodyComponent& component);

}  // namespace filum::mechanics
