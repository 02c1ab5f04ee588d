#include "filum/visual/vtp_writer.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace filum::visual {

namespace {

std::string exact(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

std::ofstream openOrThrow(const std::string& path) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  return out;
}

}  // namespace

void writeVtp(const std::string& path, const std::vector<PolyLine>& lines, const std::string& scalar_name) {
  long points = 0;
  for (const PolyLine& line : lines) {
    if (!line.points.allFinite()) throw std::runtime_error(path + ": refusing to write non-finite points of " + line.name);
    points += line.points.rows();
  }
  std::ofstream out = openOrThrow(path);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << points << "\" NumberOfVerts=\"0\" NumberOfLines=\"" << lines.size()
      << "\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const PolyLine& line : lines)
    for (Eigen::Index i = 0; i < line.points.rows(); ++i)
      out << "          " << exact(line.points(i, 0)) << ' ' << exact(line.points(i, 1)) << ' '
          << exact(line.points(i, 2)) << '\n';
  out << "        </DataArray>\n      </Points>\n"
      << "      <PointData Scalars=\"" << scalar_name << "\">\n"
      << "        <DataArray type=\"Float64\" Name=\"" << scalar_name << "\" format=\"ascii\">\n";
  for (const PolyLine& line : lines)
    for (Eigen::Index i = 0; i < line.points.rows(); ++i)
      out << "          " << exact(i < static_cast<Eigen::Index>(line.scalars.size()) ? line.scalars[i] : 0.0) << '\n';
  out << "        </DataArray>\n      </PointData>\n"
      << "      <CellData Scalars=\"body\">\n        <DataArray type=\"Int32\" Name=\"body\" format=\"ascii\">\n";
  for (std::size_t k = 0; k < lines.size(); ++k) out << "          " << k << '\n';
  out << "        </DataArray>\n      </CellData>\n"
      << "      <Lines>\n        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  long next = 0;
  for (const PolyLine& line : lines) {
    out << "         ";
    for (Eigen::Index i = 0; i < line.points.rows(); ++i) out << ' ' << next++;
    out << '\n';
  }
  out << "        </DataArray>\n        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  long offset = 0;
  for (const PolyLine& line : lines) out << "          " << (offset += line.points.rows()) << '\n';
  out << "        </DataArray>\n      </Lines>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  out.close();  // flushes: a full disk or a file size limit shows here, not in a destructor
  if (!out) throw std::runtime_error(path + ": write failed (disk full or file size limit?)");
}

void writeMeshVtp(const std::string& path, const TriangleMesh& mesh) {
  if (!mesh.vertices.allFinite() || !mesh.normals.allFinite())
    throw std::runtime_error(path + ": refusing to write non-finite mesh vertices or normals");
  std::ofstream out = openOrThrow(path);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
      << "  <PolyData>\n"
      << "    <Piece NumberOfPoints=\"" << mesh.vertexCount() << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\""
      << " NumberOfStrips=\"0\" NumberOfPolys=\"" << mesh.triangleCount() << "\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (int v = 0; v < mesh.vertexCount(); ++v)
    out << "          " << exact(mesh.vertices(v, 0)) << ' ' << exact(mesh.vertices(v, 1)) << ' '
        << exact(mesh.vertices(v, 2)) << '\n';
  out << "        </DataArray>\n      </Points>\n"
      << "      <PointData Normals=\"Normals\">\n"
      << "        <DataArray type=\"Float64\" Name=\"Normals\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (int v = 0; v < mesh.vertexCount(); ++v)
    out << "          " << exact(mesh.normals(v, 0)) << ' ' << exact(mesh.normals(v, 1)) << ' '
        << exact(mesh.normals(v, 2)) << '\n';
  out << "        </DataArray>\n      </PointData>\n"
      << "      <Polys>\n        <DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">\n";
  for (int f = 0; f < mesh.triangleCount(); ++f)
    out << "          " << mesh.triangles(f, 0) << ' ' << mesh.triangles(f, 1) << ' ' << mesh.triangles(f, 2) << '\n';
  out << "        </DataArray>\n        <DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">\n";
  for (int f = 0; f < mesh.triangleCount(); ++f) out << "          " << 3 * (f + 1) << '\n';
  out << "        </DataArray>\n      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  out.close();  // flushes: a full disk or a file size limit shows here, not in a destructor
  if (!out) throw std::runtime_error(path + ": write failed (disk full or file size limit?)");
}

}  // namespace filum::visual
