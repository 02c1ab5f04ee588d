#include "filum/haptics/wound_pad.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace filum::haptics {

WoundPad::WoundPad(double width, double thickness, double edge_radius)
    : width_(width), thickness_(thickness), edge_radius_(edge_radius) {}

void WoundPad::setEdges(const std::vector<Station>& lip0, const std::vector<Station>& lip1) {
  edges_[0] = lip0;
  edges_[1] = lip1;
  // Each slab's box: the corners of its cross-section at every station, x = P + (u − r_e) ô −
  // (v − r_e) n̂ for u ∈ {0, width}, v ∈ {0, thickness} (between stations the slab is interpolated
  // from them: within the box up to the frames' turn over a station's length, below the
  // contact reach queries add).
  speed_ = 0.0;
  for (int k = 0; k < 2; ++k) {
    lower_[k] = Vec3::Constant(std::numeric_limits<double>::infinity());
    upper_[k] = -lower_[k];
    for (const Station& st : edges_[k]) {
      for (const double u : {0.0, width_})
        for (const double v : {0.0, thickness_}) {
          const Vec3 x = st.point + (u - edge_radius_) * st.outward - (v - edge_radius_) * st.normal;
          lower_[k] = lower_[k].cwiseMin(x);
          upper_[k] = upper_[k].cwiseMax(x);
        }
      speed_ = std::max(speed_, st.velocity.norm());
    }
  }
}

void WoundPad::setPassage(const CurveBody* thread, const std::vector<std::pair<double, double>>& spans) {
  thread_ = thread;
  spans_ = spans;
}

bool WoundPad::passesThrough(const CurveBody& body, double s) const {
  if (&body != thread_) return true;  // the lips are the pad; only the thread touches it
  for (const auto& [a, b] : spans_)
    if (s >= a && s <= b) return true;
  return false;
}

bool WoundPad::sample(const Vec3& x, double max_distance, collision::SurfaceSample& out) const {
  collision::SurfaceSample lip;
  bool found = false;
  for (int k = 0; k < 2; ++k) {
    // Farther than max_distance outside the slab's box: farther from the slab too.
    if ((x - lower_[k]).minCoeff() < -max_distance || (upper_[k] - x).minCoeff() < -max_distance) continue;
    if (!sampleLip(edges_[k], x, max_distance, lip)) continue;
    if (!found || lip.distance < out.distance) out = lip;
    found = true;
  }
  return found;
}

bool WoundPad::sampleLip(const std::vector<Station>& edge, const Vec3& x, double max_distance,
                         collision::SurfaceSample& out) const {
  if (edge.size() < 2) return false;
  // The nearest segment of the edge's polyline, and where x projects on it.
  std::size_t best = 0;
  double best_tau = 0.0, best_d2 = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < edge.size(); ++i) {
    const Vec3 a = edge[i].point, ab = edge[i + 1].point - a;
    const double tau = std::clamp((x - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
    const double d2 = (x - a - tau * ab).squaredNorm();
    if (d2 < best_d2) {
      best_d2 = d2;
      best = i;
      best_tau = tau;
    }
  }
  const Station &s0 = edge[best], &s1 = edge[best + 1];
  const Vec3 p = (1.0 - best_tau) * s0.point + best_tau * s1.point;
  // Beyond an end of the edge: no skin there.
  if ((best == 0 && best_tau == 0.0 && (x - p).dot(s0.tangent) < 0.0) ||
      (best + 2 == edge.size() && best_tau == 1.0 && (x - p).dot(s1.tangent) > 0.0))
    return false;
  const Vec3 t = ((1.0 - best_tau) * s0.tangent + best_tau * s1.tangent).normalized();
  const Vec3 n0 = (1.0 - best_tau) * s0.normal + best_tau * s1.normal;
  const Vec3 n = (n0 - n0.dot(t) * t).normalized();
  const Vec3 o0 = (1.0 - best_tau) * s0.outward + best_tau * s1.outward;
  const Vec3 o = (o0 - o0.dot(t) * t - o0.dot(n) * n).normalized();
  const double u = (x - p).dot(o) + edge_radius_, v = -(x - p).dot(n) + edge_radius_;
  // The rectangle [0, width] × [0, thickness] in (u, v); u along ô, v along −n̂.
  double distance;
  Vec3 normal;
  if (u >= 0.0 && u <= width_ && v >= 0.0 && v <= thickness_) {
    const double faces[4] = {u, width_ - u, v, thickness_ - v};  // cut face, far side, skin, bottom
    const Vec3 outward[4] = {-o, o, n, -n};
    const int nearest = static_cast<int>(std::min_element(faces, faces + 4) - faces);
    distance = -faces[nearest];
    normal = outward[nearest];
  } else {
    const double du = u - std::clamp(u, 0.0, width_), dv = v - std::clamp(v, 0.0, thickness_);
    distance = std::hypot(du, dv);
    normal = (du * o - dv * n) / distance;
  }
  if (distance > max_distance) return false;
  out.distance = distance;
  out.normal = normal;
  out.point = x - distance * normal;
  out.velocity = (1.0 - best_tau) * s0.velocity + best_tau * s1.velocity;
  return true;
}

}  // namespace filum::haptics
