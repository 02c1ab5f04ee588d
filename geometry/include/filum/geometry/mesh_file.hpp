// Mesh files: the one reader of filum for surface meshes (organs, vessels, tissue pads), used by
// collision (TriangleMeshSurface, built into a CGAL mesh) and by visual (MeshModel). It reads
// what real exporters (Blender, MeshLab, 3D Slicer, CAD tools) write, which CGAL's OBJ reader
// refuses:
//   - OBJ (obj_mesh_reader.cpp): "v x y z" (extra numbers such as vertex colours ignored), "f"
//     faces of 3 or more corners in the forms "i", "i/t", "i//n", "i/t/n" (1-based, or negative:
//     relative to the last vertex); every other line ("vt", "vn", "g", "group", "o", "s",
//     "mtllib", "usemtl", ...) is ignored;
//   - OFF (off_mesh_reader.cpp): "[C][N][ST]OFF", "V F [E]", V vertex lines (extra numbers
//     ignored), F faces "n i_1 ... i_n" (0-based; a face colour after them ignored), "#" comments;
//   - PLY (ply_mesh_reader.cpp): ascii, binary_little_endian, binary_big_endian; the "vertex"
//     element's x, y, z (any numeric type) and the "face" element's "vertex_indices" (or
//     "vertex_index") list; other properties and elements are skipped;
//   - STL (stl_mesh_reader.cpp): ascii ("solid" ... "endsolid") and binary (80-byte header,
//     triangle count, 50 bytes a triangle); corners with the same coordinates are merged into one
//     vertex, so that the mesh is connected (CGAL's inside test needs a closed surface), and the
//     triangles that merging collapses are dropped;
//   - VTP (vtp_mesh_reader.cpp): VTK XML PolyData, the format of 3D Slicer, VMTK and ParaView:
//     one Piece, its Points, Polys and triangle Strips (connectivity and offsets), inline in
//     format "ascii" or "binary" (base64, UInt32 or UInt64 header, either byte order, any numeric
//     type), or "appended" (VTK's default: raw or base64 after the XML); binary data compressed
//     by zlib or not (other compressors are refused with how to save the file instead).
// Every format: lines may end in LF, CRLF or CR; words may be separated by any run of spaces and
// tabs; polygons are fanned into triangles (v0, v_k, v_{k+1}); coordinates are in the file's own
// units (the scene's "units" and "scale" turn them into metres: mesh_units.hpp).
//
// Robustness (the parser sees untrusted bytes, and is fuzzed): no input crashes it, hangs it or
// makes it allocate beyond the limits below. Counts announced by a header are checked against
// the bytes that follow before anything is allocated for them (compressed data: each block's
// compressed bytes are read before its inflated size, which zlib bounds, is allocated, and the
// whole is checked against the Piece's counts first); integers are parsed with overflow
// checks; indices are checked against the vertices; non-finite coordinates are refused. Every
// refusal is a std::runtime_error "name:line: expected ..., found ..." (binary data: "name: byte
// N: ...").
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include <Eigen/Core>

#include "filum/core/types.hpp"

namespace filum::geometry {

/// F triangles, one per row: indices into the vertices, in the file's order of corners.
using TriangleIndices = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

/// A mesh as read: vertices and triangles, no connectivity checks (a closed surface, a manifold
/// are the user's business: TriangleMeshSurface checks them).
struct PolygonSoup {
  Points vertices;            // V × 3, finite, in the file's units
  TriangleIndices triangles;  // F × 3, each index in [0, V)
};

enum class MeshFormat { kObj, kOff, kPly, kStl, kVtp };

/// Vertices of a mesh file, at most: 4e6 vertices (96 MB of coordinates) is beyond what a step's
/// collision queries or a frame's drawing can use (the same bound as a skin's,
/// visual/generalized_cylinder_model.hpp: kMaxSkinVertices).
inline constexpr long kMaxMeshVertices = 4000000;
/// Triangles, at most: a closed surface of V vertices has about 2V triangles (Euler).
inline constexpr long kMaxMeshTriangles = 2 * kMaxMeshVertices;

/// Parses `bytes` as a mesh of the given format; `name` (a path) goes into the messages.
/// At most kMaxMeshFileBytes bytes (input_file.hpp), kMaxMeshVertices vertices and
/// kMaxMeshTriangles triangles. Throws std::runtime_error naming `name` and the line (or byte)
/// for malformed input, with what was expected and what was found; at least one triangle.
PolygonSoup readMesh(std::string_view bytes, MeshFormat format, const std::string& name);

/// The format of a path by its extension, case-insensitive (.obj, .off, .ply, .stl, .vtp). Throws
/// std::runtime_error "path: expected ..., found ..." for any other.
MeshFormat meshFormatOfPath(const std::string& path);

/// Reads a mesh file: checks that it is a regular file of at most kMaxMeshFileBytes
/// (inputFileProblem: no FIFO, no device), reads it and parses it with readMesh.
PolygonSoup readMeshFile(const std::string& path);

}  // namespace filum::geometry
