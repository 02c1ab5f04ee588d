// The one translation unit of filum that includes CGAL (see triangle_mesh_surface.hpp).
#include "filum/collision/triangle_mesh_surface.hpp"

#include <array>
#include <cmath>
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
  std::unique_ptr<Inside> inside;  // closed meshes only
  bool closed = false;
  // Angle-weighted pseudo-normals (Bærentzen & Aanæs 2005): per face its unit normal, per edge
  // the sum of its (one or two) faces' normals, per vertex Σ_f α_f n_f with α_f the face's angle
  // at the vertex; and which edges and vertices lie on a border.
  std::vector<Vec3> face_normal, edge_normal, vertex_normal;
  std::vector<char> edge_border, vertex_border;
  // The hint of the next closest-point query: the answer to the last one. Without a hint CGAL
  // looks one up in a k-d tree of reference points, which allocates on every query; queries come
  // sphere after sphere along a thread, so the last answer is close to the next one. The answer
  // does not depend on the hint (it only prunes the tree traversal sooner).
  mutable Tree::Point_and_primitive_id hint;
};

TriangleMeshSurface::TriangleMeshSurface(const Points& vertices, const std::vector<Triangle>& triangles, bool allow_open)
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
  m.closed = CGAL::is_closed(m.mesh);
  if (!m.closed && !allow_open)
    throw std::invalid_argument("the mesh is not closed (it has border edges); the inside test needs a closed surface");
  m.tree = std::make_unique<Tree>(faces(m.mesh).first, faces(m.mesh).second, m.mesh);
  m.tree->build();
  m.hint = m.tree->any_reference_point_and_id();
  if (m.closed) m.inside = std::make_unique<Inside>(m.mesh);
  computePseudoNormals();
}

void TriangleMeshSurface::computePseudoNormals() {
  Impl& m = *impl_;
  const Mesh& mesh = m.mesh;
  m.face_normal.assign(mesh.number_of_faces(), Vec3::Zero());
  m.edge_normal.assign(mesh.number_of_edges(), Vec3::Zero());
  m.vertex_normal.assign(mesh.number_of_vertices(), Vec3::Zero());
  m.edge_border.assign(mesh.number_of_edges(), 0);
  m.vertex_border.assign(mesh.number_of_vertices(), 0);
  for (const auto f : mesh.faces()) {
    auto h = mesh.halfedge(f);
    const Vec3 a = toVec3(mesh.point(mesh.source(h))), b = toVec3(mesh.point(mesh.target(h))),
               c = toVec3(mesh.point(mesh.target(mesh.next(h))));
    const Vec3 n = (b - a).cross(c - a).normalized();  // counter-clockwise seen from outside: outwards
    m.face_normal[f.idx()] = n;
    for (int k = 0; k < 3; ++k, h = mesh.next(h)) {
      m.edge_normal[mesh.edge(h).idx()] += n;
      // The angle at target(h) between its two edges in this face.
      const Vec3 p = toVec3(mesh.point(mesh.source(h))), q = toVec3(mesh.point(mesh.target(h))),
                 r = toVec3(mesh.point(mesh.target(mesh.next(h))));
      const double angle = std::atan2((p - q).cross(r - q).norm(), (p - q).dot(r - q));
      m.vertex_normal[mesh.target(h).idx()] += angle * n;
    }
  }
  for (const auto h : mesh.halfedges())
    if (mesh.is_border(h)) {
      m.edge_border[mesh.edge(h).idx()] = 1;
      m.vertex_border[mesh.source(h).idx()] = m.vertex_border[mesh.target(h).idx()] = 1;
    }
  for (Vec3& n : m.edge_normal) n.normalize();
  for (Vec3& n : m.vertex_normal) n.normalize();
}

bool TriangleMeshSurface::closed() const { return impl_->closed; }

double TriangleMeshSurface::enclosedVolume(double& scale) const {
  const Mesh& mesh = impl_->mesh;
  double volume = 0.0;
  scale = 0.0;
  const auto add = [&](const Vec3& a, const Vec3& b, const Vec3& c) {
    const double v = a.dot(b.cross(c)) / 6.0;
    volume += v;
    scale += std::abs(v);
  };
  for (const auto f : mesh.faces()) {
    const auto h = mesh.halfedge(f);
    add(toVec3(mesh.point(mesh.source(h))), toVec3(mesh.point(mesh.target(h))),
        toVec3(mesh.point(mesh.target(mesh.next(h)))));
  }
  // Each hole: its border halfedges form a cycle wound as a face filling it would be (Surface_mesh
  // keeps a manifold mesh's borders so); a fan from the cycle's centroid closes it.
  std::vector<char> seen(mesh.number_of_halfedges(), 0);
  for (const auto start : mesh.halfedges()) {
    if (!mesh.is_border(start) || seen[start.idx()]) continue;
    Vec3 centroid = Vec3::Zero();
    int count = 0;
    auto h = start;
    do {
      seen[h.idx()] = 1;
      centroid += toVec3(mesh.point(mesh.source(h)));
      ++count;
      h = mesh.next(h);
    } while (h != start);
    centroid /= count;
    do {
      add(centroid, toVec3(mesh.point(mesh.source(h))), toVec3(mesh.point(mesh.target(h))));
      h = mesh.next(h);
    } while (h != start);
  }
  return volume;
}

std::unique_ptr<TriangleMeshSurface> TriangleMeshSurface::reversed() const {
  std::vector<Triangle> flipped = impl_->triangles;
  for (Triangle& t : flipped) std::swap(t[1], t[2]);
  return std::make_unique<TriangleMeshSurface>(impl_->vertices, flipped, true);
}

TriangleMeshSurface::ClosestFeature TriangleMeshSurface::closestFeature(const Vec3& x) const {
  const Impl& m = *impl_;
  const Mesh& mesh = m.mesh;
  ClosestFeature out;
  out.point = closestPoint(x);
  // Which feature of the closest face c lies on, by its barycentric coordinates (λ_a, λ_b, λ_d)
  // in the face a b d: a coordinate below round-off (relative 1e-9: the closest point is
  // computed to ~1e-16 of the face's size) puts c on the opposite edge, two of them on a vertex.
  const auto f = m.hint.second;
  const auto h = mesh.halfedge(f);
  const std::array<Mesh::Halfedge_index, 3> edges{mesh.next(h), mesh.next(mesh.next(h)), h};  // opposite a, b, d
  const std::array<Mesh::Vertex_index, 3> corners{mesh.source(h), mesh.target(h), mesh.target(mesh.next(h))};
  const Vec3 a = toVec3(mesh.point(corners[0])), b = toVec3(mesh.point(corners[1])), d = toVec3(mesh.point(corners[2]));
  const Vec3 n = (b - a).cross(d - a);
  const double area2 = n.squaredNorm();
  // A face of no area (three corners on a line, common in segmented meshes) has no normal and no
  // barycentric coordinates: c lies on its longest edge, whose pseudo-normal is its neighbour's.
  const double longest2 = std::max({(b - a).squaredNorm(), (d - b).squaredNorm(), (a - d).squaredNorm()});
  if (!(area2 > 1e-24 * longest2 * longest2)) {
    const int k = (d - b).squaredNorm() == longest2 ? 0 : (a - d).squaredNorm() == longest2 ? 1 : 2;
    const auto e = mesh.edge(edges[k]);
    out.normal = m.edge_normal[e.idx()];
    out.on_border = m.edge_border[e.idx()] != 0;
    return out;
  }
  std::array<double, 3> lambda{(d - b).cross(out.point - b).dot(n) / area2, (a - d).cross(out.point - d).dot(n) / area2,
                               (b - a).cross(out.point - a).dot(n) / area2};
  constexpr double kOnFeature = 1e-9;
  int small = 0, last_small = -1, largest = 0;
  for (int k = 0; k < 3; ++k) {
    if (lambda[k] <= kOnFeature) {
      ++small;
      last_small = k;
    }
    if (lambda[k] > lambda[largest]) largest = k;
  }
  if (small >= 2) {
    const auto v = corners[largest];
    out.normal = m.vertex_normal[v.idx()];
    out.on_border = m.vertex_border[v.idx()] != 0;
  } else if (small == 1) {
    const auto e = mesh.edge(edges[last_small]);
    out.normal = m.edge_normal[e.idx()];
    out.on_border = m.edge_border[e.idx()] != 0;
  } else {
    out.normal = m.face_normal[f.idx()];
  }
  return out;
}

TriangleMeshSurface::~TriangleMeshSurface() = default;

std::unique_ptr<TriangleMeshSurface> TriangleMeshSurface::read(const std::string& path, double scale,
                                                               const Vec3& translation, bool allow_open) {
  // filum's reader (mesh_file.hpp), not CGAL's: CGAL's OBJ reader refuses common exports
  // (groups, materials, "v/vt/vn" corners), and ours checks the file before reading it.
  geometry::PolygonSoup soup = geometry::readMeshFile(path);
  const Points vertices = (scale * soup.vertices).rowwise() + translation.transpose();
  std::vector<Triangle> triangles(static_cast<std::size_t>(soup.triangles.rows()));
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int c = 0; c < 3; ++c) triangles[f][c] = soup.triangles(static_cast<Eigen::Index>(f), c);
  try {
    return std::make_unique<TriangleMeshSurface>(vertices, triangles, allow_open);
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
  if (!impl_->inside) throw std::logic_error("TriangleMeshSurface::inside on an open mesh (it has no inside)");
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
