// The only translation unit that includes CGAL (compile time): see convolution_surface_mesher.hpp.
#include "filum/visual/convolution_surface_mesher.hpp"

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <stdexcept>
#include <vector>

#include <CGAL/Complex_2_in_triangulation_3.h>
#include <CGAL/IO/facets_in_complex_2_to_triangle_mesh.h>
#include <CGAL/Implicit_surface_3.h>
#include <CGAL/Random.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/Surface_mesh_default_triangulation_3.h>
#include <CGAL/make_surface_mesh.h>

#include <Eigen/Geometry>

namespace filum::visual {

namespace {

using Triangulation = CGAL::Surface_mesh_default_triangulation_3;
using Complex = CGAL::Complex_2_in_triangulation_3<Triangulation>;
using Kernel = Triangulation::Geom_traits;
using Point = Kernel::Point_3;
using FT = Kernel::FT;

// f: negative inside, positive outside, as CGAL's Implicit_surface_3 expects.
struct FunctionAdapter {
  const ImplicitFunction* f;
  FT operator()(const Point& p) const { return (*f)(Vec3(p.x(), p.y(), p.z())); }
};

using Surface = CGAL::Implicit_surface_3<Kernel, FunctionAdapter>;

/// The triangles in one order whatever order CGAL's complex lists them in (its facets are keyed by
/// address, so two meshings of one surface in a process list them differently): each rotated to
/// start at its smallest vertex, keeping its orientation, then sorted.
void sortTriangles(Triangles& triangles) {
  std::vector<std::array<int, 3>> rows(static_cast<std::size_t>(triangles.rows()));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    int first = 0;
    for (int k = 1; k < 3; ++k)
      if (triangles(f, k) < triangles(f, first)) first = k;
    for (int k = 0; k < 3; ++k) rows[f][k] = triangles(f, (first + k) % 3);
  }
  std::sort(rows.begin(), rows.end());
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) triangles(f, k) = rows[f][k];
}

}  // namespace

bool convolutionSurfaceMeshingAvailable() { return true; }

TriangleMesh meshConvolutionSurface(const geometry::ConvolutionSurface& surface, const Vec3& inside,
                                    double bounding_radius, const SurfaceMeshingCriteria& criteria) {
  if (!(surface.implicitValue(inside) < 0.0))
    throw std::invalid_argument("meshConvolutionSurface: the start point is not inside the surface");
  // f = T − F, outward gradient ∇f = −∇F.
  return meshImplicitSurface([&](const Vec3& x) { return surface.implicitValue(x); },
                             [&](const Vec3& x) { return Vec3(-surface.fieldGradient(x)); }, inside, bounding_radius,
                             criteria);
}

TriangleMesh meshImplicitSurface(const ImplicitFunction& value, const ImplicitGradient& gradient, const Vec3& inside,
                                 double bounding_radius, const SurfaceMeshingCriteria& criteria) {
  if (!(value(inside) < 0.0)) throw std::invalid_argument("meshImplicitSurface: the start point is not inside the surface");
  Triangulation triangulation;
  Complex complex(triangulation);
  const FunctionAdapter function{&value};
  // Error bound of the bisection that locates surface points on segments: a small fraction of
  // the approximation bound.
  const Surface implicit(function, Kernel::Sphere_3(Point(inside.x(), inside.y(), inside.z()), bounding_radius * bounding_radius),
                         1e-3 * criteria.approximation / bounding_radius);
  const CGAL::Surface_mesh_default_criteria_3<Triangulation> bounds(criteria.angle_degrees, criteria.facet_size,
                                                                   criteria.approximation);
  // The mesher's initial points on the surface are drawn from CGAL's default random generator,
  // seeded from the clock: seeded here, so that a scene gives the same meshes on every run
  // (determinism), whatever was meshed before.
  CGAL::get_default_random() = CGAL::Random(0);
  CGAL::make_surface_mesh(complex, implicit, bounds, CGAL::Manifold_tag());
  CGAL::Surface_mesh<Point> output;
  CGAL::facets_in_complex_2_to_triangle_mesh(complex, output);
  if (output.number_of_faces() == 0) throw std::runtime_error("meshImplicitSurface: CGAL produced no facets");

  TriangleMesh mesh;
  mesh.vertices.resize(output.number_of_vertices(), 3);
  mesh.normals.resize(output.number_of_vertices(), 3);
  std::map<CGAL::Surface_mesh<Point>::Vertex_index, int> index;
  int next = 0;
  for (auto v : output.vertices()) {
    const Point& p = output.point(v);
    const Vec3 x(p.x(), p.y(), p.z());
    mesh.vertices.row(next) = x.transpose();
    const Vec3 g = gradient(x);  // outward
    mesh.normals.row(next) = (g.norm() > 0.0 ? Vec3(g.normalized()) : Vec3::UnitZ()).transpose();
    index[v] = next++;
  }
  mesh.triangles.resize(output.number_of_faces(), 3);
  int f = 0;
  for (auto face : output.faces()) {
    int k = 0;
    for (auto v : CGAL::vertices_around_face(output.halfedge(face), output)) mesh.triangles(f, k++) = index[v];
    // Counter-clockwise seen from outside: the face normal agrees with the field normals.
    const Vec3 a = mesh.vertices.row(mesh.triangles(f, 0)).transpose(), b = mesh.vertices.row(mesh.triangles(f, 1)).transpose(),
               c = mesh.vertices.row(mesh.triangles(f, 2)).transpose();
    const Vec3 n = mesh.normals.row(mesh.triangles(f, 0)).transpose() + mesh.normals.row(mesh.triangles(f, 1)).transpose() +
                   mesh.normals.row(mesh.triangles(f, 2)).transpose();
    if ((b - a).cross(c - a).dot(n) < 0.0) std::swap(mesh.triangles(f, 1), mesh.triangles(f, 2));
    ++f;
  }
  sortTriangles(mesh.triangles);
  return mesh;
}

}  // namespace filum::visual
