#include "filum/visual/wound_visual.hpp"

#include <array>

#include "filum/core/curve_body.hpp"

namespace filum::visual {

WoundVisual::WoundVisual(const haptics::Wound& wound, int lip) : wound_(wound), lip_(lip) {
  setName("wound lip " + std::to_string(lip));
  setMaterial(Material{Vec3(0.87, 0.62, 0.55), 1.0});  // skin
}

void WoundVisual::update(const SceneState& s) {
  const haptics::Wound::Settings& set = wound_.settings();
  // The slab's four corners at each station: A the cut face at the skin, B across, C across and
  // down, D down.
  std::vector<std::array<Vec3, 4>> corners(kStations);
  for (int i = 0; i < kStations; ++i) {
    const double u = static_cast<double>(i) / (kStations - 1);
    const haptics::WoundPad::Station frame = wound_.edgeAt(s, lip_, u);
    const Vec3 &p = frame.point, &n = frame.normal, &o = frame.outward;
    // x(u, v) = P + (u − r_e) ô − (v − r_e) n̂ at the rectangle's corners (haptics/wound.hpp).
    const double r = set.edge_radius;
    const auto at = [&](double u, double v) { return Vec3(p + (u - r) * o - (v - r) * n); };
    corners[i] = {at(0, 0), at(set.width, 0), at(set.width, set.thickness), at(0, set.thickness)};
  }
  // Flat faces: each quad its own four vertices with the face's normal.
  std::vector<Vec3> v, nrm;
  std::vector<std::array<int, 3>> tri;
  auto quad = [&](const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& d) {
    // a b c d counter-clockwise seen from outside.
    const Vec3 normal = (b - a).cross(d - a).normalized();
    const int first = static_cast<int>(v.size());
    for (const Vec3* x : {&a, &b, &c, &d}) {
      v.push_back(*x);
      nrm.push_back(normal);
    }
    tri.push_back({first, first + 1, first + 2});
    tri.push_back({first, first + 2, first + 3});
  };
  for (int i = 0; i + 1 < kStations; ++i)
    for (int f = 0; f < 4; ++f) {
      const Vec3 &a = corners[i][f], &b = corners[i][(f + 1) % 4], &c = corners[i + 1][(f + 1) % 4],
                 &d = corners[i + 1][f];
      quad(a, d, c, b);
    }
  const auto& first = corners.front();
  const auto& last = corners.back();
  quad(first[0], first[1], first[2], first[3]);
  quad(last[0], last[3], last[2], last[1]);
  // Outward by construction when ô = n̂ × t̂; the other lip (ô = −n̂ × t̂) is mirrored: turn its faces.
  const bool flip = wound_.side(lip_) < 0.0;
  mesh_.vertices.resize(static_cast<int>(v.size()), 3);
  mesh_.normals.resize(static_cast<int>(v.size()), 3);
  mesh_.triangles.resize(static_cast<int>(tri.size()), 3);
  for (std::size_t k = 0; k < v.size(); ++k) {
    mesh_.vertices.row(k) = v[k].transpose();
    mesh_.normals.row(k) = (flip ? -nrm[k] : nrm[k]).transpose();
  }
  for (std::size_t k = 0; k < tri.size(); ++k)
    mesh_.triangles.row(k) << tri[k][0], flip ? tri[k][2] : tri[k][1], flip ? tri[k][1] : tri[k][2];
}

}  // namespace filum::visual
