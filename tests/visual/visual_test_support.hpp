// Shared pieces of the visual tests: a factory with the visual components, small scenes built
// in code, the closed-2-manifold check of triangle meshes, and the display check (Xvfb).
#pragma once

#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "filum/core/scene_error.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/visual/convolution_surface_mesher.hpp"
#include "filum/visual/display_server.hpp"
#include "filum/visual/offscreen_renderer.hpp"
#include "filum/visual/triangle_mesh.hpp"
#include "support/library_components.hpp"

namespace filum::test {

inline Factory visualFactory() { return libraryComponents(); }

/// In a build without CGAL: expects loading `document` (which holds a CGAL-meshed skin) to be
/// refused with an error naming FILUM_WITH_CGAL, and returns true — the caller's test ends there.
/// With CGAL: false, nothing checked.
inline bool refusedWithoutCgal(const nlohmann::json& document, const std::string& source) {
  if (visual::convolutionSurfaceMeshingAvailable()) return false;
  try {
    loadScene(document, source, visualFactory());
    ADD_FAILURE() << "a CGAL-meshed skin was accepted without CGAL";
  } catch (const SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("FILUM_WITH_CGAL"), std::string::npos) << e.what();
  }
  return true;
}

/// A scene with one spline through `points` (no gravity unless given), plus `more` components
/// in the thread's node; "camera" added if not null.
inline nlohmann::json splineScene(const nlohmann::json& points, const nlohmann::json& more, double radius = 2e-3,
                                  const nlohmann::json& camera = nullptr) {
  nlohmann::json components = nlohmann::json::array();
  components.push_back({{"type", "DynamicSpline"}, {"control_points", points}, {"mass", 1e-3}, {"radius", radius}});
  for (const auto& c : more) components.push_back(c);
  nlohmann::json scene{{"name", "visual test"},
                       {"dt", 1e-4},
                       {"gravity", {0.0, 0.0, 0.0}},
                       {"nodes", nlohmann::json::array({{{"name", "thread"}, {"components", components}}})}};
  if (!camera.is_null()) scene["camera"] = camera;
  return scene;
}

/// A scene with one straight rod (FramedChain, silicone's 1150 kg/m³) along x from 0 to `length`
/// with `nodes` nodes and radius `shaft`, thinner (`tip`) from abscissa `tip_from` to its end
/// ("spans"), plus `more` components in its node; no gravity.
inline nlohmann::json rodWithThinTip(double length, int nodes, double shaft, double tip_from, double tip,
                                     const nlohmann::json& more) {
  nlohmann::json components = nlohmann::json::array();
  components.push_back({{"type", "FramedChain"},
                        {"nodes", {{"from", {0, 0, 0}}, {"to", {length, 0, 0}}, {"count", nodes}}},
                        {"radius", shaft},
                        {"density", 1150},
                        {"spans", {{{"from", tip_from}, {"to", 1.0}, {"radius", tip}}}}});
  for (const auto& c : more) components.push_back(c);
  return {{"name", "visual test"},
          {"dt", 1e-4},
          {"gravity", {0.0, 0.0, 0.0}},
          {"nodes", nlohmann::json::array({{{"name", "rod"}, {"components", components}}})}};
}

/// Control points of a planar wave in the xy-plane: x from 0 to 0.1 m, y = a sin(2π x / 0.05).
inline nlohmann::json planarWave(int n = 20, double amplitude = 0.01) {
  nlohmann::json points = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    const double x = 0.1 * i / (n - 1);
    points.push_back({x, amplitude * std::sin(2.0 * 3.141592653589793 * x / 0.05), 0.0});
  }
  return points;
}

/// A helix around z: radius 0.02 m, pitch 0.03 m, 1.5 turns (non-planar, torsion).
inline nlohmann::json helix(int n = 24) {
  nlohmann::json points = nlohmann::json::array();
  for (int i = 0; i < n; ++i) {
    const double a = 3.0 * 3.141592653589793 * i / (n - 1);
    points.push_back({0.02 * std::cos(a), 0.02 * std::sin(a), 0.03 * a / (2.0 * 3.141592653589793)});
  }
  return points;
}

struct ManifoldReport {
  bool closed = true;                 // every edge in exactly two triangles
  bool consistently_oriented = true;  // each directed edge once (neighbours traverse it oppositely)
  bool vertex_manifold = true;        // the triangles around each vertex form one cycle
  int euler_characteristic = 0;       // V − E + F (2 for a sphere-like surface)
  bool no_degenerate = true;          // no triangle repeats a vertex
  std::string first_problem;
};

/// Topological checks of a triangle mesh (after welding vertices closer than `weld`, if > 0).
inline ManifoldReport checkClosedManifold(const visual::TriangleMesh& mesh, double weld = 0.0) {
  ManifoldReport r;
  // Welding: map each vertex to the first one within `weld` (quadratic; meshes here are small).
  std::vector<int> id(mesh.vertexCount());
  int unique = 0;
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    id[v] = v;
    if (weld > 0.0)
      for (int u = 0; u < v; ++u)
        if (id[u] == u && (mesh.vertices.row(u) - mesh.vertices.row(v)).norm() <= weld) {
          id[v] = u;
          break;
        }
    if (id[v] == v) ++unique;
  }
  std::map<std::pair<int, int>, int> directed;
  std::map<std::pair<int, int>, int> undirected;
  std::map<int, std::vector<std::pair<int, int>>> link;  // vertex → opposite edges (b, c) of its triangles
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const int a = id[mesh.triangles(f, 0)], b = id[mesh.triangles(f, 1)], c = id[mesh.triangles(f, 2)];
    if (a == b || b == c || a == c) {
      r.no_degenerate = false;
      if (r.first_problem.empty()) r.first_problem = "degenerate triangle " + std::to_string(f);
      continue;
    }
    const int t[3] = {a, b, c};
    for (int k = 0; k < 3; ++k) {
      const int p = t[k], q = t[(k + 1) % 3];
      if (++directed[{p, q}] > 1) {
        r.consistently_oriented = false;
        if (r.first_problem.empty()) r.first_problem = "directed edge used twice";
      }
      ++undirected[{std::min(p, q), std::max(p, q)}];
      link[p].push_back({q, t[(k + 2) % 3]});
    }
  }
  for (const auto& [edge, count] : undirected)
    if (count != 2) {
      r.closed = false;
      if (r.first_problem.empty())
        r.first_problem = "edge " + std::to_string(edge.first) + "-" + std::to_string(edge.second) + " in " +
                          std::to_string(count) + " triangles";
    }
  for (auto& [v, edges] : link) {
    // The link of v: edges (b → c); follow them from the first and count the cycle length.
    std::map<int, int> next;
    for (const auto& [b, c] : edges) next[b] = c;
    int length = 0, at = edges.front().first;
    do {
      if (!next.count(at)) break;
      at = next[at];
      ++length;
    } while (at != edges.front().first && length <= static_cast<int>(edges.size()));
    if (length != static_cast<int>(edges.size()) || at != edges.front().first) {
      r.vertex_manifold = false;
      if (r.first_problem.empty()) r.first_problem = "vertex " + std::to_string(v) + " is not a manifold vertex";
    }
  }
  r.euler_characteristic = unique - static_cast<int>(undirected.size()) + mesh.triangleCount();
  return r;
}

/// Signed volume enclosed by the triangles (divergence theorem): positive if they face outward.
inline double signedVolume(const visual::TriangleMesh& mesh) {
  double volume = 0.0;
  for (int f = 0; f < mesh.triangleCount(); ++f) {
    const Vec3 a = mesh.vertices.row(mesh.triangles(f, 0)).transpose(), b = mesh.vertices.row(mesh.triangles(f, 1)).transpose(),
               c = mesh.vertices.row(mesh.triangles(f, 2)).transpose();
    volume += a.dot(b.cross(c)) / 6.0;
  }
  return volume;
}

/// The X display the rendering tests draw on, one for the whole test program (an Xvfb started here
/// when DISPLAY is unset); nullptr, with the reason, when there is none. Xvfb is a dependency of
/// every build with OpenCV (scripts/setup.sh installs it), so its absence is a failure, not a skip.
inline std::shared_ptr<visual::DisplayServer> renderingDisplay(std::string& why) {
  static std::shared_ptr<visual::DisplayServer> server;
  if (server) return server;
  const char* display = std::getenv("DISPLAY");
  if ((!display || !*display) && !visual::DisplayServer::xvfbInstalled()) {
    why = "no X display: DISPLAY is unset and Xvfb, a dependency of this build, is not installed (Debian package "
          "xvfb: scripts/setup.sh installs it)";
    return nullptr;
  }
  server = visual::DisplayServer::ensure();  // throws (the test fails) if Xvfb is installed but does not start
  return server;
}

}  // namespace filum::test

// At the top of a test that renders: skipped only in a build without OpenCV, which renders nothing
// (its `filum run --render` and `filum view` say so); failed when no X display can be had.
#define FILUM_REQUIRE_RENDERING()                                                                         \
  do {                                                                                                    \
    if (!::filum::visual::renderingAvailable())                                                           \
      GTEST_SKIP() << "built without OpenCV (FILUM_WITH_OPENCV=OFF): this build renders nothing";        \
    std::string filum_no_display;                                                                         \
    ASSERT_NE(::filum::test::renderingDisplay(filum_no_display), nullptr) << filum_no_display;            \
  } while (0)
