// Convolution (skeleton) implicit surfaces around a skeleton of segments (Bloomenthal &
// Shoemake, "Convolution surfaces", SIGGRAPH 1991; kernel and closed form of McCormack &
// Sherstyuk 1998, see cauchy_segment_kernel.hpp). The field is the kernel integrated along the
// whole skeleton,
//   F(x) = Σ_segments ∫ k(|x − c(t)|) dt,
// so a polyline gives a smooth tube with no bulge at its joints (the line integral is additive:
// splitting a segment does not change F). The surface is F(x) = T. [Lenoir talk 2008] renders
// intestines this way and uses f(x) = 0 for catheter contact against vessels built on an
// animated skeleton: collision test by the sign of f, response along ∇f.
//
// Iso-value: chosen so that the surface around one isolated straight segment passes at the
// desired radius R at its middle, T = F_L(R) = 2 I2(L/2) (cauchySegmentMidplaneField); with
// L = ∞ (the default) T = π/(2 s (1 + s²R²)^{3/2}), the radius of a long straight tube.
//
// A tube whose section changes along it (a rod's spans) weights each segment, F(x) = Σ w_i ∫ k:
// a long straight tube of weight w passes where w F_∞(r) = T, so the weight that gives it the
// radius r is w(r) = T / F_∞(r) = T · 2 s (1 + s²r²)^{3/2} / π (weightForRadius), with the
// surface's one kernel; where the weight steps, the field blends the two tubes over about 1/s.
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "filum/core/types.hpp"
#include "filum/geometry/cauchy_segment_kernel.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::geometry {

class ConvolutionSurface {
 public:
  /// radius > 0: the radius R of the tube around a straight skeleton (units of length);
  /// sharpness s > 0 of the Cauchy kernel (1/units of length), 0 means s = 1/R; larger s blends
  /// less between nearby parts of the skeleton. reference_segment_length L > 0: the iso-value is
  /// set for an isolated segment of that length (infinity: a long tube). Throws std::invalid_argument.
  explicit ConvolutionSurface(double radius, double sharpness = 0.0,
                              double reference_segment_length = std::numeric_limits<double>::infinity());

  /// A segment of weight w > 0 (1: a tube of the surface's radius; weightForRadius).
  void addSegment(const Vec3& a, const Vec3& b, double weight = 1.0);
  /// Consecutive points joined by segments (m >= 2 points, m − 1 segments).
  void addPolyline(ConstPointsRef points);
  /// The curve (basis, q) as a polyline of `segments` >= 1 chords at equal arc-length spacing;
  /// one strand of a cut curve (CurveBasis::strands), the whole curve by default. With
  /// `radius_at` (m at an abscissa), each chord's weight gives the radius at its middle abscissa.
  void addCurve(const CurveBasis& basis, ConstPointsRef q, int segments, const Strand& strand = {},
                const std::function<double(double)>& radius_at = {});
  /// w(r) = T / F_∞(r): the weight with which a long straight tube has radius r > 0 (header).
  double weightForRadius(double r) const;
  void clear() { segments_.clear(); }

  /// F(x) (units of length).
  double field(const Vec3& x) const;
  /// ∇F(x).
  Vec3 fieldGradient(const Vec3& x) const;
  /// F and ∇F together (one pass over the skeleton).
  SegmentField fieldAndGradient(const Vec3& x) const;
  /// f(x) = T − F(x): negative inside, zero on the surface, positive outside; ∇f = −∇F points outwards.
  double implicitValue(const Vec3& x) const { return iso_value_ - field(x); }

  double isoValue() const { return iso_value_; }
  double radius() const { return radius_; }
  double sharpness() const { return sharpness_; }
  int segmentCount() const { return static_cast<int>(segments_.size()); }

 private:
  struct Segment {
    Vec3 a, b;
    double weight = 1.0;
  };
  double radius_;
  double sharpness_;
  double iso_value_;
  std::vector<Segment> segments_;
};

}  // namespace filum::geometry
