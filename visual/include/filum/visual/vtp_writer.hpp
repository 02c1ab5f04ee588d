// VTK XML PolyData (.vtp) files and ParaView .pvd series, so that ParaView plays a run.
// ASCII with 17 significant digits: files are exact and bit-identical between identical runs.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "filum/core/types.hpp"

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

/// A ParaView collection (.pvd) of time steps; rewritten whole after each add, so the index on
/// disk always lists every file written so far.
class PvdSeries {
 public:
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  /// Records a dataset file (path relative to the .pvd) at time t and rewrites the index.
  void add(double time, const std::string& relative_file);
  const std::vector<std::pair<double, std::string>>& entries() const { return entries_; }

 private:
  std::string path_;
  std::vector<std::pair<double, std::string>> entries_;
};

}  // namespace filum::visual
