#include "filum/visual/ply_reader.hpp"

#include "filum/core/input_file.hpp"

#include <algorithm>
#include <bit>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace filum::visual {

namespace {

enum class Format { kAscii, kLittleEndian, kBigEndian };

struct Property {
  std::string name;
  std::string type;        // scalar type, or the item type of a list
  std::string count_type;  // list only: the type of the count
  bool list = false;
};

struct Element {
  std::string name;
  long count = 0;
  std::vector<Property> properties;
};

int typeSize(const std::string& type) {
  if (type == "char" || type == "uchar" || type == "int8" || type == "uint8") return 1;
  if (type == "short" || type == "ushort" || type == "int16" || type == "uint16") return 2;
  if (type == "int" || type == "uint" || type == "int32" || type == "uint32" || type == "float" || type == "float32")
    return 4;
  if (type == "double" || type == "float64") return 8;
  return 0;
}

class Reader {
 public:
  Reader(std::istream& in, Format format, const std::string& path) : in_(in), format_(format), path_(path) {}

  /// The next value of the given PLY type, as a double.
  double next(const std::string& type) {
    if (format_ == Format::kAscii) {
      double v;
      if (!(in_ >> v)) fail("unexpected end of data or a non-number");
      return v;
    }
    const int size = typeSize(type);
    unsigned char bytes[8];
    if (!in_.read(reinterpret_cast<char*>(bytes), size)) fail("unexpected end of binary data");
    const bool swap = (format_ == Format::kLittleEndian) != (std::endian::native == std::endian::little);
    if (swap)
      for (int i = 0; i < size / 2; ++i) std::swap(bytes[i], bytes[size - 1 - i]);
    if (type == "char" || type == "int8") return static_cast<std::int8_t>(bytes[0]);
    if (type == "uchar" || type == "uint8") return bytes[0];
    if (type == "short" || type == "int16") return as<std::int16_t>(bytes);
    if (type == "ushort" || type == "uint16") return as<std::uint16_t>(bytes);
    if (type == "int" || type == "int32") return as<std::int32_t>(bytes);
    if (type == "uint" || type == "uint32") return as<std::uint32_t>(bytes);
    if (type == "float" || type == "float32") return as<float>(bytes);
    return as<double>(bytes);
  }

  [[noreturn]] void fail(const std::string& what) const { throw std::runtime_error(path_ + ": " + what); }

 private:
  template <class T>
  static double as(const unsigned char* bytes) {
    T value;
    std::memcpy(&value, bytes, sizeof value);
    return static_cast<double>(value);
  }
  std::istream& in_;
  Format format_;
  const std::string& path_;
};

}  // namespace

TriangleMesh readPly(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path + ": cannot open the mesh file");
  std::string line;
  if (!std::getline(in, line) || line.substr(0, 3) != "ply") throw std::runtime_error(path + ": not a PLY file (no \"ply\" magic)");
  // Header.
  Format format = Format::kAscii;
  std::vector<Element> elements;
  bool has_format = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    std::istringstream words(line);
    std::string tag;
    words >> tag;
    if (tag == "end_header") break;
    if (tag == "format") {
      std::string name;
      words >> name;
      if (name == "ascii")
        format = Format::kAscii;
      else if (name == "binary_little_endian")
        format = Format::kLittleEndian;
      else if (name == "binary_big_endian")
        format = Format::kBigEndian;
      else
        throw std::runtime_error(path + ": unknown PLY format \"" + name + "\"");
      has_format = true;
    } else if (tag == "element") {
      Element e;
      words >> e.name >> e.count;
      elements.push_back(e);
    } else if (tag == "property") {
      if (elements.empty()) throw std::runtime_error(path + ": property before any element");
      Property p;
      words >> p.type;
      if (p.type == "list") {
        p.list = true;
        words >> p.count_type >> p.type;
        if (!typeSize(p.count_type)) throw std::runtime_error(path + ": unknown PLY type \"" + p.count_type + "\"");
      }
      words >> p.name;
      if (!typeSize(p.type)) throw std::runtime_error(path + ": unknown PLY type \"" + p.type + "\"");
      elements.back().properties.push_back(p);
    }
  }
  if (!has_format) throw std::runtime_error(path + ": PLY header without \"format\" or \"end_header\"");

  // Data, element by element; only vertex x, y, z and face vertex lists are kept.
  Reader reader(in, format, path);
  TriangleMesh mesh;
  std::vector<Eigen::Vector3i> triangles;
  long vertex_count = 0;
  const std::uintmax_t file_bytes = inputFileSize(path);
  for (const Element& e : elements) {
    // Before allocating: an entry takes at least one byte per property (binary char).
    const auto entry_bytes = static_cast<long double>(std::max<std::size_t>(1, e.properties.size()));
    if (e.count < 0 || e.count * entry_bytes > static_cast<long double>(file_bytes))
      throw std::runtime_error(path + ": element '" + e.name + "' announces " + std::to_string(e.count) +
                               " entries of " + std::to_string(e.properties.size()) + " properties in a file of " +
                               std::to_string(file_bytes) + " bytes (at least one byte per property)");
    const bool vertex = e.name == "vertex", face = e.name == "face";
    if (vertex) {
      vertex_count = e.count;
      mesh.vertices.setZero(e.count, 3);
    }
    for (long i = 0; i < e.count; ++i) {
      for (const Property& p : e.properties) {
        if (p.list) {
          const double announced = reader.next(p.count_type);
          // Checked before the list is allocated: a list holds at most one entry per byte of the file.
          if (!(announced >= 0.0 && announced <= static_cast<double>(file_bytes)))
            reader.fail("element " + std::to_string(i) + ": a list of " + std::to_string(announced) +
                        " entries in a file of " + std::to_string(file_bytes) + " bytes");
          const long n = static_cast<long>(announced);
          std::vector<int> polygon(n);
          for (long k = 0; k < n; ++k) polygon[k] = static_cast<int>(reader.next(p.type));
          if (face && (p.name == "vertex_indices" || p.name == "vertex_index")) {
            if (n < 3) reader.fail("face " + std::to_string(i) + " has fewer than 3 vertices");
            for (int index : polygon)
              if (index < 0 || index >= vertex_count)
                reader.fail("face " + std::to_string(i) + ": vertex index " + std::to_string(index) + " out of range");
            for (long k = 1; k + 1 < n; ++k) triangles.emplace_back(polygon[0], polygon[k], polygon[k + 1]);
          }
        } else {
          const double value = reader.next(p.type);
          if (vertex) {
            const int axis = p.name == "x" ? 0 : p.name == "y" ? 1 : p.name == "z" ? 2 : -1;
            if (axis >= 0) mesh.vertices(i, axis) = value;
          }
        }
      }
    }
  }
  if (!mesh.vertices.allFinite()) throw std::runtime_error(path + ": non-finite vertex coordinates");
  if (triangles.empty()) throw std::runtime_error(path + ": no faces");
  mesh.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t f = 0; f < triangles.size(); ++f) mesh.triangles.row(static_cast<Eigen::Index>(f)) = triangles[f].transpose();
  mesh.normals.setZero(mesh.vertices.rows(), 3);
  return mesh;
}

}  // namespace filum::visual
