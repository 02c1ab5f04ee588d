// VTK XML PolyData (.vtp) files — polylines (sampled curves) and triangle meshes (the visual
// models) — for ParaView, with .pvd series (pvd_series.hpp) so that ParaView plays a run.
// ASCII with 17 significant digits: files are exact and bit-identical between identical runs.
#pragma once

#include <string>
#include <vector>

#include "filum/core/types.hpp"
#include "filum/visual/pvd_series.hpp"
#include "filum/visual/triangle_mesh.hpp"

namespace filum::visual {

/// One polyline (e.g. a sampled curve or a control polygon) with one scalar per point.
struct PolyLine {
  std::string name;              // body name (for the "body" cell data)
  Points points;                 // m, one per row
  std::vector<double> scalars;   // per point (e.g. abscissa s); may be empty
};

/// Writes the polylines as one PolyData piece with a per-cell "body" index and a per-point
/// scalar array named `scalar_name`. Throws std::runtime_error if the file cannot be written or
/// a coordinate is not finite (nothing non-finite is ever written).
void writeVtp(const std::string& path, const std::vector<PolyLine>& lines, const std::string& scalar_name);

/// Writes one triangle mesh as a PolyData piece: Points, point data "Normals" (3 components)
/// and Polys (triangles). Throws std::runtime_error if the file cannot be written or a value is
/// not finite.
void writeMeshVtp(const std::string& path, const TriangleMesh& mesh);

}  // namespace filum::visual
