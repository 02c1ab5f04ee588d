#include "filum/visual/obj_writer.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace filum::visual {

void writeObj(const std::string& path, const std::vector<NamedMesh>& meshes) {
  for (const NamedMesh& m : meshes)
    if (!m.mesh->vertices.allFinite() || !m.mesh->normals.allFinite())
      throw std::runtime_error(path + ": refusing to write non-finite vertices of " + m.name);
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << "# filum visual meshes\n";
  char buffer[96];
  long first = 1;  // OBJ indices are 1-based and global to the file
  for (const NamedMesh& m : meshes) {
    const TriangleMesh& mesh = *m.mesh;
    out << "o " << m.name << '\n';
    for (int v = 0; v < mesh.vertexCount(); ++v) {
      std::snprintf(buffer, sizeof buffer, "v %.9g %.9g %.9g\n", mesh.vertices(v, 0), mesh.vertices(v, 1), mesh.vertices(v, 2));
      out << buffer;
    }
    for (int v = 0; v < mesh.vertexCount(); ++v) {
      std::snprintf(buffer, sizeof buffer, "vn %.9g %.9g %.9g\n", mesh.normals(v, 0), mesh.normals(v, 1), mesh.normals(v, 2));
      out << buffer;
    }
    for (int f = 0; f < mesh.triangleCount(); ++f) {
      const long a = first + mesh.triangles(f, 0), b = first + mesh.triangles(f, 1), c = first + mesh.triangles(f, 2);
      out << "f " << a << "//" << a << ' ' << b << "//" << b << ' ' << c << "//" << c << '\n';
    }
    first += mesh.vertexCount();
  }
  out.close();  // flushes: a full disk or a file size limit shows here, not in a destructor
  if (!out) throw std::runtime_error(path + ": write failed (disk full or file size limit?)");
}

}  // namespace filum::visual
