#include "filum/visual/ply_writer.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace filum::visual {

void writePly(const std::string& path, const TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite() || !mesh.normals.allFinite())
    throw std::runtime_error(path + ": refusing to write non-finite vertices");
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << "ply\nformat ascii 1.0\ncomment filum visual mesh\n"
      << "element vertex " << mesh.vertexCount() << '\n'
      << "property float x\nproperty float y\nproperty float z\n"
      << "property float nx\nproperty float ny\nproperty float nz\n"
      << "element face " << mesh.triangleCount() << '\n'
      << "property list uchar int vertex_indices\nend_header\n";
  char buffer[160];
  for (int v = 0; v < mesh.vertexCount(); ++v) {
    std::snprintf(buffer, sizeof buffer, "%.9g %.9g %.9g %.9g %.9g %.9g\n", mesh.vertices(v, 0), mesh.vertices(v, 1),
                  mesh.vertices(v, 2), mesh.normals(v, 0), mesh.normals(v, 1), mesh.normals(v, 2));
    out << buffer;
  }
  for (int f = 0; f < mesh.triangleCount(); ++f)
    out << "3 " << mesh.triangles(f, 0) << ' ' << mesh.triangles(f, 1) << ' ' << mesh.triangles(f, 2) << '\n';
  out.close();  // flushes: a full disk or a file size limit shows here, not in a destructor
  if (!out) throw std::runtime_error(path + ": write failed (disk full or file size limit?)");
}

}  // namespace filum::visual
