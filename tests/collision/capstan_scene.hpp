// A cord hanging over a fixed horizontal peg by its own weight (the capstan with the cord's weight
// counted), for the capstan test and apps/scenes/capstan*.json (apps/tools/make_capstan.py writes
// the same geometry).
//
// Material: a silicone cord (a vessel loop): radius 1 mm, density 1100 kg/m³, Young's modulus
// 1 MPa for stretching (cured silicone rubber, 1-3 MPa), so w = ρ A g = 0.0339 N/m; 5 /s of viscous
// damping (air and internal losses). The peg: a steel pin of radius 3 cm, the cord on it with
// friction μ. Implicit Euler steps of 1 ms, contacts as unilateral rows of the constraint solve.
//
// Bending: the capstan equation is that of a perfectly flexible cord, and a solid cord is not one
// at this scale. With the rubber's own 1 MPa, E I = E π r⁴/4 = 7.85e-7 N·m², and the cord's
// bending boundary layer where it meets the peg, ℓ = √(EI/T), is 10 mm on the light side
// (T = w L1 = 8.5e-3 N) and 5 mm on the heavy one: a third and a sixth of ρ_c. Measured: such a
// cord leaves the peg 0.3 rad before the light arm's tangent point and 0.16 rad before the heavy
// one's (the free span turns by about ℓ/ρ_c without touching), and it holds 4 % less than the
// capstan limit at μ = 0.4, 2 % less at μ = 0.2 (slides at 0.96 and at 0.98 of L2_max with
// h = 5 mm). The test cord bends with `bending_modulus` = 1 kPa instead — E I = 7.85e-10 N·m²,
// ℓ <= 0.3 mm = 1 % of ρ_c: the flexible cord the equation describes. apps/scenes/capstan*.json
// keep the solid cord's 1 MPa (apps/tools/make_capstan.py).
//
// Geometry: the light arm hangs at x = +ρ_c (ρ_c = R + r, the centre line's radius on the peg)
// from z = 0 down to −L1, the cord wraps over the top half of the peg, the heavy arm hangs at
// x = −ρ_c down to −L2. Control points every `spacing` along that path (5 mm: the discrete cord
// holds about 1.5 % less than the continuous one there, less at a finer spacing, capstan_test.cpp);
// those on the arc are set
// out by (1 + h²/(6ρ_c²)) so that the cubic B-spline, which lies inside its control polygon by
// about h²/(6ρ_c) on a circle, starts on the peg.
//
// Settling. The cord starts unstretched and at rest, so its arms first fall and then ring with
// stretch waves that briefly load the heavy side to nearly twice its weight: the peg slips, and
// since every millimetre slipped moves weight from the light arm to the heavy one, a start at 2 %
// below the limit runs away after 7 mm. The material point on top of the peg is therefore pinned
// (a FixedPointConstraint released at `settle`) while the arms stretch and their waves damp out
// (e^{−5·settle/2}: 8 % left after 1 s; settling 3 s instead moved no threshold, measured with
// the solid cord at μ = 0.4); from then on only friction holds the cord.
#pragma once

#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

namespace filum::test {

struct CapstanCord {
  double peg_radius = 0.03;   // R (m)
  double radius = 1e-3;       // r (m)
  double density = 1100.0;    // kg/m³
  double youngs_modulus = 1e6;  // Pa (stretching)
  double bending_modulus = 1e3; // Pa (a flexible cord, above)
  double damping = 5.0;       // 1/s
  double friction = 0.3;      // μ
  double light_arm = 0.25;    // L1 (m)
  double heavy_arm = 0.5;     // L2 (m)
  double spacing = 0.005;     // control points (m)
  double dt = 1e-3;           // s
  double settle = 1.0;        // s: the pin on top of the peg is released then
  double duration = 3.0;      // s

  double wrapRadius() const { return peg_radius + radius; }  // ρ_c
};

/// Control points along the arms and the arc, from the light arm's end to the heavy arm's.
inline nlohmann::json capstanControlPoints(const CapstanCord& c) {
  const double rc = c.wrapRadius(), h = c.spacing;
  const double arc = M_PI * rc;
  const double length = c.light_arm + arc + c.heavy_arm;
  const int count = static_cast<int>(std::lround(length / h)) + 1;
  const double step = length / (count - 1);
  const double bulge = 1.0 + step * step / (6.0 * rc * rc);
  nlohmann::json points = nlohmann::json::array();
  for (int i = 0; i < count; ++i) {
    const double s = i * step;
    double x, z;
    if (s <= c.light_arm) {
      x = rc;
      z = -(c.light_arm - s);
    } else if (s <= c.light_arm + arc) {
      const double theta = (s - c.light_arm) / rc;  // from the light side's horizontal, over the top
      x = bulge * rc * std::cos(theta);
      z = bulge * rc * std::sin(theta);
    } else {
      x = -rc;
      z = -(s - c.light_arm - arc);
    }
    points.push_back({x, 0.0, z});
  }
  return points;
}

/// The abscissa of the material point that starts on top of the peg.
inline double capstanTopAbscissa(const CapstanCord& c) {
  const double arc = M_PI * c.wrapRadius();
  return (c.light_arm + 0.5 * arc) / (c.light_arm + arc + c.heavy_arm);
}

inline nlohmann::json capstanScene(const CapstanCord& c) {
  using nlohmann::json;
  json thread = {
      {"name", "cord"},
      {"components",
       {{{"type", "DynamicSpline"}, {"basis", "uniform_cubic_bspline"}, {"radius", c.radius}, {"density", c.density},
         {"control_points", capstanControlPoints(c)}},
        {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", c.youngs_modulus}, {"jacobian", "definite"}},
        {{"type", "ParametricBending"}, {"youngs_modulus", c.bending_modulus}},
        {{"type", "ViscousDamping"}, {"coefficient", c.damping}},
        {{"type", "SphereCollisionModel"}, {"spacing", 2.0 * c.radius}},
        {{"type", "FixedPointConstraint"}, {"name", "settling pin"}, {"abscissa", capstanTopAbscissa(c)},
         {"release_at", c.settle}}}}};
  json peg = {{"type", "CapsuleObstacle"}, {"name", "peg"}, {"a", {0.0, -0.05, 0.0}}, {"b", {0.0, 0.05, 0.0}},
              {"radius", c.peg_radius}, {"friction", c.friction}};
  json scene = json{{"name", "capstan"},
              {"dt", c.dt},
              {"duration", c.duration},
              {"gravity", {0.0, 0.0, -9.81}},
              {"integrator", {{"type", "ImplicitEuler"}}},
              {"collision", {{"type", "ContactPipeline"}, {"response", "unilateral"}}},
              {"components", {peg}},
              {"nodes", {thread}}};
  return scene;
}

/// The heaviest arm the peg holds, from the capstan equation with the cord's weight on the peg.
/// With θ from the light side's horizontal over the top, the cord's element r dθ under tension T,
/// the peg's normal force N and friction F (per unit angle) and its weight w ρ_c dθ:
///   normal:     N = T + w ρ_c sin θ;
///   tangential: dT/dθ = −F + w ρ_c cos θ, and at impending slip towards the heavy side F = −μ N:
///   dT/dθ = μ T + w ρ_c (cos θ + μ sin θ).
/// Integrated over the half turn (the particular solution e^{μ(π−θ)}(a sin θ + b cos θ) with
/// a = (1 − μ²)/(1 + μ²), b = −2μ/(1 + μ²)):
///   T(π) = e^{μπ} T(0) + w ρ_c · 2μ (1 + e^{μπ}) / (1 + μ²).
/// The arms hang straight, T(0) = w L1 and T(π) = w L2, so the peg holds L2 up to
///   L2_max = e^{μπ} L1 + ρ_c · 2μ (1 + e^{μπ}) / (1 + μ²).
inline double capstanHeaviestArm(double mu, double light_arm, double wrap_radius) {
  const double e = std::exp(mu * M_PI);
  return e * light_arm + wrap_radius * 2.0 * mu * (1.0 + e) / (1.0 + mu * mu);
}

}  // namespace filum::test
