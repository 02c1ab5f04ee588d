#include "filum/geometry/convolution_surface.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "filum/geometry/arc_length.hpp"

namespace filum::geometry {

ConvolutionSurface::ConvolutionSurface(double radius, double sharpness, double reference_segment_length)
    : radius_(radius), sharpness_(sharpness == 0.0 ? 1.0 / radius : sharpness) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("ConvolutionSurface: radius must be positive and finite, got " + std::to_string(radius));
  if (!(sharpness_ > 0.0) || !std::isfinite(sharpness_))
    throw std::invalid_argument("ConvolutionSurface: sharpness must be positive and finite (or 0 for 1/radius), got " +
                                std::to_string(sharpness));
  if (!(reference_segment_length > 0.0))
    throw std::invalid_argument("ConvolutionSurface: reference_segment_length must be positive, got " +
                                std::to_string(reference_segment_length));
  iso_value_ = cauchySegmentMidplaneField(radius_, reference_segment_length, sharpness_);
}

void ConvolutionSurface::addSegment(const Vec3& a, const Vec3& b, double weight) {
  if (!a.allFinite() || !b.allFinite()) throw std::invalid_argument("ConvolutionSurface::addSegment: non-finite end");
  if (!(weight > 0.0) || !std::isfinite(weight))
    throw std::invalid_argument("ConvolutionSurface::addSegment: weight must be positive and finite, got " +
                                std::to_string(weight));
  segments_.push_back({a, b, weight});
}

double ConvolutionSurface::weightForRadius(double r) const {
  if (!(r > 0.0) || !std::isfinite(r))
    throw std::invalid_argument("ConvolutionSurface::weightForRadius: radius must be positive and finite, got " +
                                std::to_string(r));
  // w = T / F_∞(r), F_∞ the field of an infinite straight segment at distance r (header).
  return iso_value_ / cauchyLineField(r, sharpness_);
}

void ConvolutionSurface::addPolyline(ConstPointsRef points) {
  if (points.rows() < 2)
    throw std::invalid_argument("ConvolutionSurface::addPolyline: need at least 2 points, got " +
                                std::to_string(points.rows()));
  for (Eigen::Index i = 0; i + 1 < points.rows(); ++i)
    addSegment(points.row(i).transpose(), points.row(i + 1).transpose());
}

void ConvolutionSurface::addCurve(const CurveBasis& basis, ConstPointsRef q, int segments, const Strand& strand,
                                  const std::function<double(double)>& radius_at) {
  if (segments < 1)
    throw std::invalid_argument("ConvolutionSurface::addCurve: segments must be >= 1, got " + std::to_string(segments));
  const ArcLengthParameterization arc(basis, q, 1e-10);
  const std::vector<double> s = arc.equallySpacedAbscissas(segments + 1, strand);
  const Points points = arc.pointsAt(s, strand);
  if (!radius_at) {
    addPolyline(points);
    return;
  }
  for (int i = 0; i < segments; ++i)
    addSegment(points.row(i).transpose(), points.row(i + 1).transpose(),
               weightForRadius(radius_at(0.5 * (s[i] + s[i + 1]))));
}

SegmentField ConvolutionSurface::fieldAndGradient(const Vec3& x) const {
  SegmentField total;
  for (const Segment& segment : segments_) {
    const SegmentField f = cauchySegmentField(segment.a, segment.b, x, sharpness_);
    total.value += segment.weight * f.value;
    total.gradient += segment.weight * f.gradient;
  }
  return total;
}

double ConvolutionSurface::field(const Vec3& x) const {
  double total = 0.0;
  for (const Segment& segment : segments_)
    total += segment.weight * cauchySegmentIntegral(segment.a, segment.b, x, sharpness_);
  return total;
}

Vec3 ConvolutionSurface::fieldGradient(const Vec3& x) const { return fieldAndGradient(x).gradient; }

}  // namespace filum::geometry
