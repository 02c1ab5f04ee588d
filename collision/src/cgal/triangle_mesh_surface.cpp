// The one translation unit of filum that includes CGAL (see triangle_mesh_surface.hpp).
#include "filum/collision/triangle_mesh_surface.hpp"

#include <stdexcept>

#include "filum/geometry/mesh_file.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Simple_cartesian.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/helpers.h>

namespace filum::collision {

namespace {

// Double-precision Cartesian kernel: closest points are constructions in doubles either way, and
// Side_of_triangle_mesh re-shoots its ray when it meets a degenerate configuration.
using Kernel = CGAL::Simple_cartesian<double>;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Inside = CGAL::Side_of_triangle_mesh<Mesh, Kernel>;

Vec3 toVec3(const Point& p) { return Vec3(p.x(), p.y(), p.z()); }
Point toPoint(const Vec3& x) { return Point(x.x(), x.y(), x.z()); }

}  // namespace

struct TriangleMeshSurface::Impl {
  Points vertices;
  std::vector<Triangle> triangles;
  Eigen::AlignedBox3d bounds;
  Mesh mesh;
  std::unique_ptr<Tree> tree;
  std::unique_ptr<Inside> inside;
  // The hint of the next closest-point query: the answer to the last one. Without a hint CGAL
  // looks one up in a k-d tree of reference points, which allocates on every query; queries come
  // sphere after sphere along a thread, so the last answer is close to the next one. The answer
  // does not depend on the hint (it only prunes the tree traversal sooner).
  mutable Tree::Point_and_primitive_id hint;
};

TriangleMeshSurface::TriangleMeshSurface(const Points& vertices, const std::vector<Triangle>& triangles)
    : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.vertices = vertices;
  m.triangles = triangles;
  if (triangles.empty()) throw std::invalid_argument("the mesh has no triangles");
  std::vector<Mesh::Vertex_index> index;
  index.reserve(vertices.rows());
  for (int v = 0; v < vertices.rows(); ++v) {
    index.push_back(m.mesh.add_vertex(toPoint(vertices.row(v).transpose())));
    m.bounds.extend(Vec3(vertices.row(v).transpose()));
  }
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    const Triangle& t = triangles[f];
    for (int c = 0; c < 3; ++c)
      if (t[c] < 0 || t[c] >= vertices.rows())
        throw std::invalid_argument("triangle " + std::to_string(f) + " uses vertex " + std::to_string(t[c]) +
                                    " of " + std::to_string(vertices.rows()));
    if (m.mesh.add_face(index[t[0]], index[t[1]], index[t[2]]) == Mesh::null_face())
      throw std::invalid_argument("triangle " + std::to_string(f) +
                                  " makes the mesh non-manifold or inconsistently oriented");
  }
  if (!CGAL::is_closed(m.mesh))
    throw std::invalid_argument("the mesh is not closed (it has border edges); the inside test needs a closed surface");
  m.tree = std::make_unique<Tree>(faces(m.mesh).first, faces(m.mesh).second, m.mesh);
  m.tree->build();
  m.hint = m.tree->any_reference_point_and_id();
  m.inside = std::make_unique<Inside>(m.mesh);
}

TriangleMeshSurface::~TriangleMeshSurface() = default;

std::unique_ptr<TriangleMeshSurface> TriangleMeshSurface::read(const std::string& path, double scale,
                                                               const Vec3& translation) {
  // filum's reader (mesh_file.hpp), not CGAL's: CGAL's OBJ reader refuses common exports
  // (groups, materials, "v/vt/vn" corners), and ours checks the file before reading it.
  geometry::PolygonSoup soup = geometry::readMeshFile(path);
  const Points vertices = (scale * soup.vertices).rowwise() + translation.transpose();
  std::vector<Triangle> triangles(static_cast<std::size_t>(soup.triangles.rows()));
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) triangles[f][c] = soup.triangles(static_cast<Eigen::Index>(f), c);
  try {
    return std::make_unique<TriangleMeshSurface>(vertices, triangles);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
}

int TriangleMeshSurface::vertexCount() const { return static_cast<int>(impl_->vertices.rows()); }
int TriangleMeshSurface::triangleCount() const { return static_cast<int>(impl_->triangles.size()); }
const Points& TriangleMeshSurface::vertices() const { return impl_->vertices; }
const std::vector<TriangleMeshSurface::Triangle>& TriangleMeshSurface::triangles() const { return impl_->triangles; }
const Eigen::AlignedBox3d& TriangleMeshSurface::bounds() const { return impl_->bounds; }

Vec3 TriangleMeshSurface::closestPoint(const Vec3& x) const {
  impl_->hint = impl_->tree->closest_point_and_primitive(toPoint(x), impl_->hint);
  return toVec3(impl_->hint.first);
}

bool TriangleMeshSurface::inside(const Vec3& x) const {
  return (*impl_->inside)(toPoint(x)) == CGAL::ON_BOUNDED_SIDE;
}

Vec3 TriangleMeshSurface::closestPoint(const Vec3& x, Vec3& face_normal) const {
  const Vec3 c = closestPoint(x);
  const Mesh& mesh = impl_->mesh;
  const auto h = mesh.halfedge(impl_->hint.second);
  const Vec3 a = toVec3(mesh.point(mesh.source(h)));
  const Vec3 b = toVec3(mesh.point(mesh.target(h)));
  const Vec3 d = toVec3(mesh.point(mesh.target(mesh.next(h))));
  face_normal = (b - a).cross(d - a).normalized();  // counter-clockwise seen from outside
  return c;
}

Vec3 TriangleMeshSurface::nearestFaceNormal(const Vec3& x) const {
  const auto hit = impl_->tree->closest_point_and_primitive(toPoint(x), impl_->hint);
  impl_->hint = hit;
  const Mesh& mesh = impl_->mesh;
  const auto h = mesh.halfedge(hit.second);
  const Vec3 a = toVec3(mesh.point(mesh.source(h)));
  const Vec3 b = toVec3(mesh.point(mesh.target(h)));
  const Vec3 c = toVec3(mesh.point(mesh.target(mesh.next(h))));
  // Counter-clockwise faces seen from outside: (b − a) × (c − a) points outwards.
  return (b - a).cross(c - a).normalized();
}

}  // namespace filum::collision
