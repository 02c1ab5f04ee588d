// WoundPad: a wound's skin (wound.hpp) as an obstacle for the thread — the two lips' slabs where
// their edges are at the step's start, moving with them — except where the thread runs in the
// tissue, between the holes the needle made in it.
//
// Each lip's edge is given as a polyline of stations (point P, unit tangent t̂, the skin's normal n̂
// made ⊥ t̂, ô = ± n̂ × t̂ away from the other lip, and the edge's velocity). A point x is projected
// on the nearest segment (its frame interpolated linearly and made orthonormal again), and its
// cross-section coordinates are
//   u = (x − P)·ô + r_e  (across, from the cut face),   v = −(x − P)·n̂ + r_e  (depth, from the skin),
// r_e the edge's radius (the edge curve is the axis of the lip's rounded edge, r_e inside both
// faces). The slab is the rectangle 0 <= u <= width, 0 <= v <= thickness; the signed distance is the
// rectangle's (negative inside: minus the distance to the nearest face), the normal points out of
// the nearest face (inside) or from the nearest rectangle point (outside), and the surface moves with
// the edge's velocity there (the lip's turning is neglected, as for its holes). Beyond the ends of
// the edge there is no skin: the slab has no end faces (a thread lying across the pad's end falls
// off it).
//
// Passage: only the wound's thread touches the pad (the lips' own spheres are the pad). The thread
// passes through the slabs at abscissas in the spans the wound sets (between its holes,
// wound.hpp), widened by kHoleMargin of thread on each side (a thread leaving its hole at 6°
// or more to the skin clears its own radius of 0.1 mm within 1 mm).
#pragma once

#include <utility>
#include <vector>

#include "filum/collision/obstacle.hpp"

namespace filum::haptics {

class WoundPad final : public collision::Obstacle {
 public:
  struct Station {
    Vec3 point = Vec3::Zero(), tangent = Vec3::UnitX(), normal = Vec3::UnitZ(), outward = Vec3::UnitY();
    Vec3 velocity = Vec3::Zero();
  };
  static constexpr double kHoleMargin = 1e-3;  // m of thread

  WoundPad(double width, double thickness, double edge_radius);
  std::string typeName() const override { return "WoundPad"; }

  /// Both lips' edges now (stations along each, at least two; copied into buffers that keep their
  /// capacity).
  void setEdges(const std::vector<Station>& lip0, const std::vector<Station>& lip1);
  /// The abscissa spans [a, b] of `thread` that run in the tissue (already widened; copied).
  void setPassage(const CurveBody* thread, const std::vector<std::pair<double, double>>& spans);
  const std::vector<std::pair<double, double>>& passage() const { return spans_; }

  bool sample(const Vec3& x, double max_distance, collision::SurfaceSample& out) const override;
  double speed() const override { return speed_; }
  bool passesThrough(const CurveBody& body, double s) const override;

 private:
  /// The slab of one lip at x, or false when x projects beyond its ends or lies farther than
  /// max_distance.
  bool sampleLip(const std::vector<Station>& edge, const Vec3& x, double max_distance,
                 collision::SurfaceSample& out) const;

  double width_, thickness_, edge_radius_;
  std::vector<Station> edges_[2];
  Vec3 lower_[2] = {Vec3::Zero(), Vec3::Zero()}, upper_[2] = {Vec3::Zero(), Vec3::Zero()};  // each slab's box
  double speed_ = 0.0;
  const CurveBody* thread_ = nullptr;
  std::vector<std::pair<double, double>> spans_;
};

}  // namespace filum::haptics
