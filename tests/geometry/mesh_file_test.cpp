// Mesh files (mesh_file.hpp): one reader for collision and visual. The quirks
// of real exports that CGAL's OBJ reader refused, one small file each; STL ascii and binary and
// PLY of both byte orders and VTP ascii and binary giving the same connected surface as an OFF; the units of a scene;
// errors that name the file and the line; headers announcing more than the file holds, refused
// before anything is allocated; and mutated files, which may only ever be refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <set>
#include <sstream>

#include <nlohmann/json.hpp>
#include <zlib.h>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/mesh_file.hpp"
#include "filum/geometry/mesh_units.hpp"

namespace filum::geometry {
namespace {

namespace fs = std::filesystem;
using namespace std::string_literals;

const std::string kData = std::string(FILUM_TEST_DATA_DIR) + "/";

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::path(FILUM_BINARY_DIR) / "test_output" / "geometry";
  fs::create_directories(dir);
  return dir / name;
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// The message of the runtime_error that reading `text` as `format` throws ("" if none).
std::string refusal(const std::string& text, MeshFormat format, const std::string& name) {
  try {
    readMesh(text, format, name);
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

struct Quirk {
  const char* file;
  int vertices, triangles;
  int vertex;     // the vertex whose coordinates are checked
  Vec3 position;  // in the file's units
};

TEST(MeshFile, ReadsTheQuirksOfRealExports) {
  const Quirk quirks[] = {
      {"obj_group_lines.obj", 4, 4, 3, Vec3(0, 0, 1)},
      {"obj_materials.obj", 4, 4, 1, Vec3(1, 0, 0)},
      {"obj_vt_vn_faces.obj", 4, 4, 2, Vec3(0, 1, 0)},
      {"obj_quads_ngons.obj", 10, 16, 6, Vec3(0.309017, 0.951057, 2)},
      {"obj_crlf.obj", 4, 4, 3, Vec3(0, 0, 1)},
      {"obj_spaces_tabs.obj", 4, 4, 1, Vec3(1, 0, 0)},
      {"obj_vertex_colours.obj", 4, 4, 3, Vec3(0, 0, 1)},
      {"obj_millimetres.obj", 4, 4, 1, Vec3(20, 0, 0)},
      {"cube.off", 8, 12, 6, Vec3(1, 1, 1)},
  };
  for (const Quirk& q : quirks) {
    const PolygonSoup soup = readMeshFile(kData + q.file);
    EXPECT_EQ(soup.vertices.rows(), q.vertices) << q.file;
    EXPECT_EQ(soup.triangles.rows(), q.triangles) << q.file;
    EXPECT_EQ(soup.vertices.row(q.vertex), q.position.transpose()) << q.file;
  }
  // The tetrahedra's faces, fanned and 0-based, whatever the form of their corners.
  const PolygonSoup corners = readMeshFile(kData + "obj_vt_vn_faces.obj");
  EXPECT_EQ(corners.triangles.row(3), Eigen::RowVector3i(1, 2, 3));
  // A pentagon (5 4 3 2 1) fans from its first corner: (4 3 2), (4 2 1), (4 1 0).
  const PolygonSoup prism = readMeshFile(kData + "obj_quads_ngons.obj");
  EXPECT_EQ(prism.triangles.row(2), Eigen::RowVector3i(4, 1, 0));
}

TEST(MeshFile, ExtensionIsCaseInsensitiveAndUnknownOnesAreRefused) {
  const fs::path upper = scratch("CUBE.OFF");
  fs::copy_file(kData + "cube.off", upper, fs::copy_options::overwrite_existing);
  EXPECT_EQ(readMeshFile(upper.string()).triangles.rows(), 12);
  const std::string message = [] {
    try {
      readMeshFile(kData + "cube.3ds");
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string();
  }();
  EXPECT_NE(message.find("cube.3ds: expected a mesh file .obj, .off, .ply, .stl or .vtp, found the extension \".3ds\""),
            std::string::npos)
      << message;
  try {
    readMeshFile(kData + "no_such_mesh.stl");
    FAIL() << "a missing file was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no_such_mesh.stl: expected a regular mesh file"), std::string::npos) << e.what();
  }
}

TEST(MeshFile, UnitsOfTheSceneMultiplyTheScale) {
  const auto scale = [](const nlohmann::json& component) {
    return meshScale(Params(component, "scene.json", "/nodes/0/components/0"));
  };
  EXPECT_EQ(scale({{"file", "organ.obj"}}), 1.0);
  EXPECT_EQ(scale({{"units", "mm"}}), 0.001);
  EXPECT_EQ(scale({{"units", "cm"}}), 0.01);
  EXPECT_EQ(scale({{"units", "m"}, {"scale", 0.5}}), 0.5);
  EXPECT_EQ(scale({{"units", "mm"}, {"scale", 2.0}}), 0.002);
  // The millimetre file in metres: its 20 mm edge is 0.02 m.
  const PolygonSoup mm = readMeshFile(kData + "obj_millimetres.obj");
  EXPECT_EQ(scale({{"units", "mm"}}) * mm.vertices(1, 0), 0.02);
  try {
    scale({{"units", "inch"}});
    FAIL() << "an unknown unit was accepted";
  } catch (const SceneError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("scene.json: /nodes/0/components/0/units"), std::string::npos) << what;
    EXPECT_NE(what.find("\"m\", \"cm\" or \"mm\""), std::string::npos) << what;
    EXPECT_NE(what.find("\"inch\""), std::string::npos) << what;
  }
  EXPECT_THROW(scale({{"units", "mm"}, {"scale", -1.0}}), SceneError);
}

// ---- The same surface in every format --------------------------------------------------------

// The triangles of `soup` as corner coordinates, each rotated to start at its smallest corner
// (orientation kept), sorted: equal for two soups of the same oriented surface, whatever the
// numbering of their vertices.
std::vector<std::array<std::array<double, 3>, 3>> canonicalTriangles(const PolygonSoup& soup) {
  std::vector<std::array<std::array<double, 3>, 3>> triangles;
  for (Eigen::Index f = 0; f < soup.triangles.rows(); ++f) {
    std::array<std::array<double, 3>, 3> t;
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) t[c][k] = soup.vertices(soup.triangles(f, c), k);
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    triangles.push_back(t);
  }
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

// Closed and connected through shared vertices: every directed edge once, its reverse once.
bool closedByIndices(const PolygonSoup& soup) {
  std::map<std::pair<int, int>, int> edges;
  for (Eigen::Index f = 0; f < soup.triangles.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++edges[{soup.triangles(f, c), soup.triangles(f, (c + 1) % 3)}];
  for (const auto& [edge, count] : edges)
    if (count != 1 || !edges.count({edge.second, edge.first})) return false;
  return true;
}

void expectSameSurface(const PolygonSoup& soup, const PolygonSoup& reference, const std::string& what) {
  EXPECT_EQ(soup.vertices.rows(), reference.vertices.rows()) << what;
  EXPECT_EQ(soup.triangles.rows(), reference.triangles.rows()) << what;
  EXPECT_TRUE(canonicalTriangles(soup) == canonicalTriangles(reference)) << what;
  EXPECT_TRUE(closedByIndices(soup)) << what << ": not connected through shared vertices";
}

template <class T>
void put(std::string& out, T value, bool big_endian = false) {
  char bytes[sizeof(T)];
  std::memcpy(bytes, &value, sizeof(T));
  if (big_endian != (std::endian::native == std::endian::big)) std::reverse(bytes, bytes + sizeof(T));
  out.append(bytes, sizeof(T));
}

// The triangles of a soup as an ascii STL, each with its own three corners.
std::string asciiStl(const PolygonSoup& soup) {
  std::ostringstream ascii;
  ascii << "solid cube\n";
  for (Eigen::Index f = 0; f < soup.triangles.rows(); ++f) {
    ascii << "  facet normal 0 0 0\n    outer loop\n";
    for (int c = 0; c < 3; ++c) {
      const auto v = soup.vertices.row(soup.triangles(f, c));
      ascii << "      vertex " << v(0) << ' ' << v(1) << ' ' << v(2) << '\n';
    }
    ascii << "    endloop\n  endfacet\n";
  }
  ascii << "endsolid cube\n";
  return ascii.str();
}

// The same as a binary STL, with a header that starts with "solid" as some exporters write it.
std::string binaryStl(const PolygonSoup& soup) {
  std::string binary = "solid cube, binary";
  binary.resize(80, ' ');
  put<std::uint32_t>(binary, static_cast<std::uint32_t>(soup.triangles.rows()));
  for (Eigen::Index f = 0; f < soup.triangles.rows(); ++f) {
    for (int k = 0; k < 3; ++k) put<float>(binary, 0.0f);
    for (int c = 0; c < 3; ++c)
      for (int k = 0; k < 3; ++k) put<float>(binary, static_cast<float>(soup.vertices(soup.triangles(f, c), k)));
    put<std::uint16_t>(binary, 0);
  }
  return binary;
}

// The unit cube of cube.off as a binary PLY: float and double coordinates with a colour between
// them, the quads as lists of uchar count and int items, and an element the reader skips.
std::string binaryPlyCube(const PolygonSoup& cube, bool big) {
  std::string ply = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                    " 1.0\ncomment made by the test\nelement vertex 8\nproperty float x\nproperty double y\n"
                    "property uchar red\nproperty float z\nelement face 6\n"
                    "property list uchar int vertex_indices\nelement camera 1\nproperty float view\nend_header\n";
  for (int v = 0; v < 8; ++v) {
    put<float>(ply, static_cast<float>(cube.vertices(v, 0)), big);
    put<double>(ply, cube.vertices(v, 1), big);
    put<std::uint8_t>(ply, 200, big);
    put<float>(ply, static_cast<float>(cube.vertices(v, 2)), big);
  }
  // The quads as they are in the OFF (the reader fans them the same way).
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (const auto& quad : quads) {
    put<std::uint8_t>(ply, 4, big);
    for (int index : quad) put<std::int32_t>(ply, index, big);
  }
  put<float>(ply, 1.5f, big);
  return ply;
}

TEST(MeshFile, StlAsciiAndBinaryGiveTheConnectedSurfaceOfTheOff) {
  const PolygonSoup cube = readMeshFile(kData + "cube.off");
  const fs::path ascii_file = scratch("cube_ascii.stl"), binary_file = scratch("cube_binary.STL");
  std::ofstream(ascii_file, std::ios::binary) << asciiStl(cube);
  std::ofstream(binary_file, std::ios::binary) << binaryStl(cube);
  expectSameSurface(readMeshFile(ascii_file.string()), cube, "ascii STL");
  expectSameSurface(readMeshFile(binary_file.string()), cube, "binary STL");
}

TEST(MeshFile, PlyOfBothByteOrdersGivesTheSurfaceOfTheOff) {
  const PolygonSoup cube = readMeshFile(kData + "cube.off");
  for (const bool big : {false, true}) {
    const fs::path file = scratch(big ? "cube_big.ply" : "cube_little.ply");
    std::ofstream(file, std::ios::binary) << binaryPlyCube(cube, big);
    const PolygonSoup soup = readMeshFile(file.string());
    expectSameSurface(soup, cube, big ? "big-endian PLY" : "little-endian PLY");
    EXPECT_TRUE(soup.triangles == cube.triangles) << "same fan";
  }
}

// Base64 (RFC 4648), written here independently of the reader.
std::string base64(const std::string& bytes) {
  static const char* alphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned a = static_cast<unsigned char>(bytes[i]);
    const unsigned b = i + 1 < bytes.size() ? static_cast<unsigned char>(bytes[i + 1]) : 0u;
    const unsigned c = i + 2 < bytes.size() ? static_cast<unsigned char>(bytes[i + 2]) : 0u;
    out += alphabet[a >> 2];
    out += alphabet[((a & 3) << 4) | (b >> 4)];
    out += i + 1 < bytes.size() ? alphabet[((b & 15) << 2) | (c >> 6)] : '=';
    out += i + 2 < bytes.size() ? alphabet[c & 63] : '=';
  }
  return out;
}

// The unit cube of cube.off as a binary VTP (VTK's XML PolyData, format="binary": base64 of a
// byte-count header and the values): Float32 points, Int32 or Int64 indices, a UInt32 or UInt64
// header, either byte order.
std::string binaryVtpCube(const PolygonSoup& cube, bool big, bool header64) {
  const auto array = [&](const std::string& values) {
    std::string block;
    if (header64)
      put<std::uint64_t>(block, values.size(), big);
    else
      put<std::uint32_t>(block, static_cast<std::uint32_t>(values.size()), big);
    return base64(block + values);
  };
  std::string points, connectivity, offsets;
  for (int v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k) put<float>(points, static_cast<float>(cube.vertices(v, k)), big);
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int f = 0; f < 6; ++f) {
    for (int index : quads[f]) put<std::int64_t>(connectivity, index, big);
    put<std::int32_t>(offsets, 4 * (f + 1), big);
  }
  return std::string("<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"") +
         (big ? "BigEndian" : "LittleEndian") + "\" header_type=\"" + (header64 ? "UInt64" : "UInt32") +
         "\">\n<PolyData>\n<Piece NumberOfPoints=\"8\" NumberOfPolys=\"6\">\n<Points>\n"
         "<DataArray type=\"Float32\" NumberOfComponents=\"3\" format=\"binary\">\n" +
         array(points) + "\n</DataArray>\n</Points>\n<Polys>\n"
         "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"binary\">" + array(connectivity) +
         "</DataArray>\n<DataArray type=\"Int32\" Name=\"offsets\" format=\"binary\">" + array(offsets) +
         "</DataArray>\n</Polys>\n</Piece>\n</PolyData>\n</VTKFile>\n";
}

TEST(MeshFile, VtpAsciiAndBinaryGiveTheSurfaceOfTheOff) {
  // A segmented surface as 3D Slicer, VMTK or ParaView save it: ascii with point data and empty
  // verts, lines and strips; binary of both byte orders and both header types.
  const PolygonSoup cube = readMeshFile(kData + "cube.off");
  const PolygonSoup ascii = readMeshFile(kData + "cube.vtp");
  expectSameSurface(ascii, cube, "ascii VTP");
  EXPECT_TRUE(ascii.triangles == cube.triangles) << "same fan";
  // Version 0.1 (no header_type: UInt32), the offsets before the connectivity.
  expectSameSurface(readMeshFile(kData + "cube_binary.vtp"), cube, "binary VTP of version 0.1");
  for (const bool big : {false, true})
    for (const bool header64 : {false, true}) {
      const std::string what = std::string(big ? "big" : "little") + "-endian binary VTP, " +
                               (header64 ? "UInt64" : "UInt32") + " header";
      const PolygonSoup soup = readMesh(binaryVtpCube(cube, big, header64), MeshFormat::kVtp, "cube.vtp");
      expectSameSurface(soup, cube, what);
      EXPECT_TRUE(soup.vertices == cube.vertices) << what;  // 0 and 1 are exact in Float32
    }
}

/// What reading `text` as "vessel.vtp" says: the refusal's message, or "(read)".
std::string vtpRefusal(const std::string& text) {
  try {
    readMesh(text, MeshFormat::kVtp, "vessel.vtp");
  } catch (const std::runtime_error& e) {
    return std::string(e.what());
  }
  return std::string("(read)");
}

// The cube again, as VTK's writers save it by default: the arrays' data after the XML in
// <AppendedData> (raw bytes, or base64), each array at its offset, compressed by zlib in blocks
// (vtkZLibDataCompressor: a header [blocks, block size, last block's size, compressed sizes], then
// the blocks). `block` bytes a block (small: several blocks, a partial last one). Inline binary
// arrays (format="binary") compressed the same way too. zlib's own compress2 is the encoder.
std::string compressedVtpCube(const PolygonSoup& cube, bool big, bool header64, const std::string& layout,
                              std::size_t block, bool zlib = true) {
  const auto word = [&](std::string& out, std::uint64_t v) {
    if (header64)
      put<std::uint64_t>(out, v, big);
    else
      put<std::uint32_t>(out, static_cast<std::uint32_t>(v), big);
  };
  // One array: header and data, as its two pieces (base64 encodes each apart, as VTK does).
  const auto pieces = [&](const std::string& values) {
    std::string header, data;
    if (!zlib) {
      word(header, values.size());
      return std::pair{header, values};
    }
    const std::size_t blocks = (values.size() + block - 1) / block;
    word(header, blocks);
    word(header, block);
    word(header, values.size() % block);
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::string part = values.substr(b * block, block);
      uLongf size = compressBound(static_cast<uLong>(part.size()));
      std::string packed(size, '\0');
      EXPECT_EQ(compress2(reinterpret_cast<Bytef*>(packed.data()), &size,
                          reinterpret_cast<const Bytef*>(part.data()), static_cast<uLong>(part.size()), 6), Z_OK);
      packed.resize(size);
      word(header, size);
      data += packed;
    }
    return std::pair{header, data};
  };
  std::string points, connectivity, offsets;
  for (int v = 0; v < 8; ++v)
    for (int k = 0; k < 3; ++k) put<double>(points, cube.vertices(v, k), big);
  const int quads[6][4] = {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {1, 2, 6, 5}, {2, 3, 7, 6}, {3, 0, 4, 7}};
  for (int f = 0; f < 6; ++f) {
    for (int index : quads[f]) put<std::int64_t>(connectivity, index, big);
    put<std::int64_t>(offsets, 4 * (f + 1), big);
  }
  std::string appended;
  const auto array = [&](const std::string& attributes, const std::string& values) {
    const auto [header, data] = pieces(values);
    if (layout == "binary") return "<DataArray " + attributes + " format=\"binary\">\n" + base64(header) + base64(data) +
                                   "\n</DataArray>\n";
    const std::string at = std::to_string(appended.size());
    appended += layout == "base64" ? base64(header) + base64(data) : header + data;
    return "<DataArray " + attributes + " format=\"appended\" offset=\"" + at + "\"/>\n";
  };
  // The arrays in a fixed order (points, connectivity, offsets: offset 0 is the points'), each
  // built in a statement of its own.
  const std::string points_array = array("type=\"Float64\" NumberOfComponents=\"3\"", points);
  const std::string connectivity_array = array("type=\"Int64\" Name=\"connectivity\"", connectivity);
  const std::string offsets_array = array("type=\"Int64\" Name=\"offsets\"", offsets);
  const std::string xml =
      "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"" +
      std::string(big ? "BigEndian" : "LittleEndian") + "\" header_type=\"" + (header64 ? "UInt64" : "UInt32") + "\"" +
      (zlib ? " compressor=\"vtkZLibDataCompressor\"" : "") +
      ">\n<PolyData>\n<Piece NumberOfPoints=\"8\" NumberOfPolys=\"6\">\n<Points>\n" + points_array +
      "</Points>\n<Polys>\n" + connectivity_array + offsets_array + "</Polys>\n</Piece>\n</PolyData>\n";
  if (layout == "binary") return xml + "</VTKFile>\n";
  return xml + "<AppendedData encoding=\"" + (layout == "base64" ? "base64" : "raw") + "\">\n   _" + appended +
         "\n</AppendedData>\n</VTKFile>\n";
}

TEST(MeshFile, VtpAsVtkSavesItByDefaultAppendedAndCompressedGivesTheSurfaceOfTheOff) {
  const PolygonSoup cube = readMeshFile(kData + "cube.off");
  for (const std::string layout : {"raw", "base64", "binary"})
    for (const bool big : {false, true})
      for (const bool header64 : {false, true})
        for (const std::size_t block : {std::size_t{40}, std::size_t{32768}}) {  // several blocks; VTK's default size
          const std::string what = layout + (big ? ", big" : ", little") + "-endian, " + (header64 ? "UInt64" : "UInt32") +
                                   " header, blocks of " + std::to_string(block) + " bytes";
          const PolygonSoup soup =
              readMesh(compressedVtpCube(cube, big, header64, layout, block), MeshFormat::kVtp, "cube.vtp");
          expectSameSurface(soup, cube, what);
          EXPECT_TRUE(soup.vertices == cube.vertices) << what;  // Float64 round trip: exact
        }
  // The same as files written by another encoder (Python's zlib): the fuzz target's seeds too.
  for (const std::string kind : {"raw", "base64"})
    expectSameSurface(readMeshFile(kData + "cube_zlib_" + kind + ".vtp"), cube, "cube_zlib_" + kind + ".vtp");
  // Appended but not compressed (ParaView's Compressor None).
  for (const std::string layout : {"raw", "base64"}) {
    const PolygonSoup soup = readMesh(compressedVtpCube(cube, false, false, layout, 0, false), MeshFormat::kVtp, "cube.vtp");
    expectSameSurface(soup, cube, layout + ", uncompressed");
  }
}

TEST(MeshFile, ABrokenCompressedOrAppendedVtpIsRefusedBeforeItsDataIsAllocated) {
  const PolygonSoup cube = readMeshFile(kData + "cube.off");
  const std::string good = compressedVtpCube(cube, false, false, "raw", 40);
  ASSERT_EQ(vtpRefusal(good), "(read)");
  const std::size_t data = good.find('_', good.find("<AppendedData")) + 1;
  // At offset 0: the points, 192 bytes in blocks of 40: a header of 3 + 5 UInt32 words, then the
  // blocks. A compressed byte flipped: zlib's check fails, named.
  std::string flipped = good;
  flipped[data + 32 + 6] = static_cast<char>(flipped[data + 32 + 6] ^ 0x55);  // inside the first block
  EXPECT_NE(vtpRefusal(flipped).find("zlib block 0"), std::string::npos) << vtpRefusal(flipped);
  // A header announcing a huge array (blocks of 2^31 − 1 bytes): refused from the Piece's counts,
  // before anything of that size is allocated.
  std::string huge = good;
  const char big_block[4] = {'\xff', '\xff', '\xff', '\x7f'};
  std::memcpy(&huge[data + 4], big_block, 4);
  EXPECT_NE(vtpRefusal(huge).find("the points of at most 192 bytes (as the Piece's counts say), found 5 blocks of "
                                  "2147483647 bytes once inflated"),
            std::string::npos)
      << vtpRefusal(huge);
  // With a UInt64 header the product would pass 2^64 (2 blocks of 2^64 − 1): refused the same way,
  // in integers.
  std::string huge64 = compressedVtpCube(cube, false, true, "raw", 40);
  const std::size_t data64 = huge64.find('_', huge64.find("<AppendedData")) + 1;
  const std::uint64_t words[3] = {2, ~std::uint64_t{0}, 1};
  std::memcpy(&huge64[data64], words, sizeof words);
  EXPECT_NE(vtpRefusal(huge64).find("found 2 blocks of 18446744073709551615 bytes once inflated"), std::string::npos)
      << vtpRefusal(huge64);
  // A block size of 0, a last block larger than the others.
  std::string zero = good;
  std::memset(&zero[data + 4], 0, 4);
  EXPECT_NE(vtpRefusal(zero).find("a block size > 0 and a last block no larger"), std::string::npos) << vtpRefusal(zero);
  // A compressed size above zlib's bound for its block.
  std::string loose = good;
  const char large[4] = {'\x00', '\x01', '\x00', '\x00'};  // 256 bytes for a block of 40
  std::memcpy(&loose[data + 12], large, 4);
  EXPECT_NE(vtpRefusal(loose).find("zlib block 0 of at most"), std::string::npos) << vtpRefusal(loose);
  // An offset beyond the appended data.
  std::string far = good;
  far.replace(far.find("offset=\"0\""), 10, "offset=\"99999\"");
  EXPECT_NE(vtpRefusal(far).find("an offset=\"n\" into the appended data"), std::string::npos) << vtpRefusal(far);
  // The data cut short: the last block's bytes end early.
  const std::string cut = good.substr(0, good.find("\n</AppendedData>") - 10);
  EXPECT_NE(vtpRefusal(cut).find("more bytes of data"), std::string::npos) << vtpRefusal(cut);
  // An unknown appended encoding.
  std::string encoding = good;
  encoding.replace(encoding.find("encoding=\"raw\""), 14, "encoding=\"hex\"");
  EXPECT_NE(vtpRefusal(encoding).find("expected <AppendedData encoding=\"raw\">"), std::string::npos) << vtpRefusal(encoding);
}

TEST(MeshFile, VtpStripsKeepOneOrientation) {
  // Triangle strips (VTK's vtkStripper): triangle k of p_0 p_1 ... is (p_k, p_k+1, p_k+2) for
  // even k and (p_k+1, p_k, p_k+2) for odd k, so that neighbours share an edge in opposite
  // directions; a repeated point (a join of two strips) gives no triangle.
  const std::string strip =
      "<VTKFile type=\"PolyData\"><PolyData><Piece NumberOfPoints=\"5\" NumberOfStrips=\"1\"><Points>"
      "<DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">0 0 0 1 0 0 0 1 0 1 1 0 2 1 0</DataArray>"
      "</Points><Strips><DataArray type=\"Int32\" Name=\"connectivity\" format=\"ascii\">0 1 2 3 3 4</DataArray>"
      "<DataArray type=\"Int32\" Name=\"offsets\" format=\"ascii\">6</DataArray></Strips></Piece></PolyData></VTKFile>";
  const PolygonSoup soup = readMesh(strip, MeshFormat::kVtp, "strip.vtp");
  TriangleIndices expected(2, 3);
  expected << 0, 1, 2, 2, 1, 3;  // (2, 3, 3) and (3, 3, 4) repeat a point: the join
  EXPECT_TRUE(soup.triangles == expected) << soup.triangles;
}

TEST(MeshFile, VtpThatCannotBeReadSaysWhatToSaveInstead) {
  const std::string ascii = fileBytes(kData + "cube.vtp");
  // The line of a text in the file (1-based), where a message must point.
  const auto lineOf = [&](const std::string& text) {
    return std::to_string(1 + std::count(ascii.begin(), ascii.begin() + static_cast<long>(ascii.find(text)), '\n'));
  };
  std::string lz4 = ascii;
  lz4.replace(lz4.find("header_type"), 0, "compressor=\"vtkLZ4DataCompressor\" ");
  EXPECT_NE(vtpRefusal(lz4).find("vessel.vtp:" + lineOf("<VTKFile") + ": expected data compressed by zlib"), std::string::npos)
      << vtpRefusal(lz4);
  std::string appended = ascii;  // an appended array in a file without <AppendedData>
  appended.replace(appended.find("format=\"ascii\" RangeMin=\"0\" RangeMax=\"1.73"), 14, "format=\"appended\" offset=\"0\"");
  EXPECT_NE(vtpRefusal(appended).find("no <AppendedData>"), std::string::npos) << vtpRefusal(appended);
  // A point that is not there: named at the line of the connectivity's values.
  std::string outside = ascii;
  outside.replace(outside.find("3 0 4 7"), 7, "3 0 4 8");
  EXPECT_NE(vtpRefusal(outside).find("vessel.vtp:" + lineOf("0 3 2 1") + ": expected indices of points"), std::string::npos)
      << vtpRefusal(outside);
  std::string not_a_number = ascii;
  not_a_number.replace(not_a_number.find("0 1 1\n"), 5, "0 1 x");
  EXPECT_NE(vtpRefusal(not_a_number).find("vessel.vtp:" + lineOf("0 0 1  1 0 1") + ": expected the points: numbers"),
            std::string::npos)
      << vtpRefusal(not_a_number);
  std::string short_offsets = ascii;
  short_offsets.replace(short_offsets.find("4 8 12 16 20 24"), 15, "4 8 12 16 20 22");
  EXPECT_NE(vtpRefusal(short_offsets).find("vessel.vtp:" + lineOf("4 8 12 16 20 24") +
                                   ": expected offsets that are whole numbers growing by at least 3 (a cell of 3 or "
                                   "more points), found offset 5 = 22 after 20"), std::string::npos) << vtpRefusal(short_offsets);
  std::string image = ascii;
  image.replace(image.find("type=\"PolyData\""), 16, "type=\"ImageData\"");
  EXPECT_NE(vtpRefusal(image).find("expected a PolyData file"), std::string::npos) << vtpRefusal(image);
}

// ---- Refusals: the file, the line, what was expected, what was found -------------------------

TEST(MeshFile, MalformedInputIsRefusedWithFileLineExpectedAndFound) {
  struct Case {
    MeshFormat format;
    const char* name;
    std::string text;
    const char* message;
  };
  const Case cases[] = {
      {MeshFormat::kObj, "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2 7\n",
       "bad.obj:3: expected vertex indices in [1, 2] or [-2, -1] (the vertices so far), found 7"},
      {MeshFormat::kObj, "bad.obj", "# colour\r\nv 0 0 zero\r\n", "bad.obj:2: expected \"v x y z\" with numbers, found \"zero\""},
      {MeshFormat::kObj, "bad.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/1 2/a 3x\n",
       "bad.obj:4: expected face corners \"i\", \"i/t\", \"i//n\" or \"i/t/n\" with a vertex index i != 0, found \"3x\""},
      {MeshFormat::kObj, "bad.obj", "v 0 0 0\nv 1e999 0 0\n", "bad.obj:2: expected \"v x y z\" with numbers, found \"1e999\""},
      {MeshFormat::kObj, "bad.obj", "v 0 0 0\nv nan 0 0\n", "bad.obj:2: expected a vertex of finite coordinates, found (nan, 0, 0)"},
      {MeshFormat::kObj, "bad.obj", "v 0 0 0\nv 1 0 0\nf 1 2\n", "bad.obj:3: expected a face of at least 3 vertices, found 2"},
      {MeshFormat::kObj, "bad.obj", "# no faces\nv 0 0 0\n", "bad.obj:2: expected at least one face, found none"},
      {MeshFormat::kOff, "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 x\n3 0 1 2\n",
       "bad.off:5: expected a vertex line \"x y z\" of numbers, found \"x\""},
      {MeshFormat::kOff, "bad.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n",
       "bad.off:6: expected vertex indices in [0, 3) (the vertices so far), found index 3"},
      {MeshFormat::kOff, "bad.off", "OFF\n99999999999999999999 1 0\n",
       "bad.off:2: expected the vertex count V of \"V F E\", found \"99999999999999999999\""},
      {MeshFormat::kOff, "bad.off", "4OFF\n", "bad.off:1: expected \"OFF\" (or COFF, NOFF, CNOFF, STOFF: a 3D ascii OFF file), found \"4OFF\""},
      {MeshFormat::kPly, "bad.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                                    "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
                                    "0 0 0\n1 0 0\n0 one 0\n3 0 1 2\n",
       "bad.ply:12: expected a number, found \"one\""},
      {MeshFormat::kPly, "bad.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float16 x\nend_header\n",
       "bad.ply:4: expected \"property <type> <name>\" with a PLY type"},
      // Three vertices of zeros, then a face announcing 3 int indices where 8 bytes are left.
      {MeshFormat::kPly, "bad.ply", "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\n"
                                    "property float y\nproperty float z\nelement face 1\n"
                                    "property list uchar int vertex_indices\nend_header\n"s +
                                        std::string(36, '\0') + "\x03"s + std::string(4, '\0') + "\x01\0\0\0"s,
       "bad.ply: byte 206: expected a list length that fits in the rest of the file (8 bytes), found 3"},
      {MeshFormat::kPly, "bad.ply", "ply\nformat binary_big_endian 1.0\nelement vertex 1\nproperty double x\n"
                                    "property double y\nproperty double z\nend_header\n"s + std::string(23, '\0'),
       "bad.ply: byte "},  // 23 bytes for 24: refused from the header
      {MeshFormat::kStl, "bad.stl", "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nendloop\n",
       "bad.stl:6: expected a facet of at least 3 vertices, found 2"},
      {MeshFormat::kStl, "bad.stl", "solid t\nfacet normal 0 0 1\n  outer lop\n", "bad.stl:3: expected \"loop\", found \"lop\""},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.text, c.format, c.name);
    EXPECT_NE(message.find(c.message), std::string::npos) << "expected: " << c.message << "\nfound:    " << message;
  }
}

TEST(MeshFile, HeaderCountsBeyondTheFileAreRefusedBeforeAllocating) {
  // Each announces far more than its bytes hold: refused from the header, at once, with the count.
  struct Case {
    MeshFormat format;
    std::string text;
    const char* message;
  };
  std::string stl(80, ' ');
  put<std::uint32_t>(stl, 4000000000u);
  stl += std::string(50, '\0');
  const Case cases[] = {
      {MeshFormat::kOff, "OFF\n1000000000 1 0\n0 0 0\n",
       "a header announcing 1000000000 vertices and 1 faces in a file of 25 bytes"},
      {MeshFormat::kOff, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n", "a face announcing 2000000000 vertices"},
      {MeshFormat::kPly, "ply\nformat binary_little_endian 1.0\nelement vertex 1000000000\nproperty float x\n"
                         "property float y\nproperty float z\nend_header\n0123456789ab",
       "a header announcing 1000000000 elements 'vertex' in a file of"},
      {MeshFormat::kPly, "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                         "element face 1\nproperty list uint int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                         "4000000000 0 1 2\n",
       "expected a list length that fits in the rest of the file"},
      {MeshFormat::kStl, stl, "a binary STL of 84 + 50 × 4000000000 = 200000000084 bytes"},
  };
  for (const Case& c : cases) {
    const std::string message = refusal(c.text, c.format, "big");
    EXPECT_NE(message.find(c.message), std::string::npos) << "expected: " << c.message << "\nfound:    " << message;
  }
}

// Every byte sequence is a mesh or a refusal: mutated and truncated copies of valid files of each
// format are read (the fuzzing targets do the same at scale); only std::runtime_error naming the
// file may come out.
TEST(MeshFile, MutatedFilesAreReadOrRefusedNeverAnythingElse) {
  const std::vector<std::pair<std::string, MeshFormat>> seeds = {
      {fileBytes(kData + "obj_vt_vn_faces.obj"), MeshFormat::kObj},
      {fileBytes(kData + "obj_quads_ngons.obj"), MeshFormat::kObj},
      {fileBytes(kData + "cube.off"), MeshFormat::kOff},
      {binaryPlyCube(readMeshFile(kData + "cube.off"), false), MeshFormat::kPly},
      {binaryStl(readMeshFile(kData + "cube.off")), MeshFormat::kStl},
      {asciiStl(readMeshFile(kData + "cube.off")), MeshFormat::kStl},
      {fileBytes(kData + "cube.vtp"), MeshFormat::kVtp},
      {binaryVtpCube(readMeshFile(kData + "cube.off"), false, true), MeshFormat::kVtp},
  };
  std::mt19937 rng(14);
  const char interesting[] = {'\0', '\n', '\r', ' ', '\t', '-', '/', '#', '9', 'e', '.', '\xff', '\x7f'};
  int read = 0, refused = 0;
  for (const auto& [seed, format] : seeds) {
    for (int trial = 0; trial < 400; ++trial) {
      std::string text = seed;
      const int edits = 1 + static_cast<int>(rng() % 4);
      for (int e = 0; e < edits && !text.empty(); ++e) {
        const std::size_t at = rng() % text.size();
        switch (rng() % 4) {
          case 0: text[at] = interesting[rng() % sizeof interesting]; break;
          case 1: text[at] = static_cast<char>(rng()); break;
          case 2: text.insert(at, 1, interesting[rng() % sizeof interesting]); break;
          case 3: text.resize(at); break;
        }
      }
      try {
        const PolygonSoup soup = readMesh(text, format, "mutant");
        ++read;
        EXPECT_TRUE(soup.vertices.allFinite());
        EXPECT_GE(soup.triangles.minCoeff(), 0);
        EXPECT_LT(soup.triangles.maxCoeff(), soup.vertices.rows());
      } catch (const std::runtime_error& e) {
        ++refused;
        EXPECT_EQ(std::string(e.what()).rfind("mutant", 0), 0u) << e.what();
      }
    }
  }
  EXPECT_GT(read, 0);
  EXPECT_GT(refused, 0);
}

}  // namespace
}  // namespace filum::geometry
