// ParaView collection (.pvd) of a time series: at each time step one dataset file per part (a
// part per visual model, or a single part), so that File ▸ Open of the .pvd plays the run.
// The index is rewritten whole (to a temporary, then renamed) after each step, so the file on
// disk always lists every dataset written so far, even if the run stops early.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace filum::visual {

class PvdSeries {
 public:
  struct Entry {
    double time;
    int part;
    std::string file;  // relative to the .pvd
  };
  explicit PvdSeries(std::string path) : path_(std::move(path)) {}
  /// Records a dataset file (path relative to the .pvd) of part 0 at time t and rewrites the index.
  void add(double time, const std::string& relative_file) { addStep(time, {relative_file}); }
  /// Records one file per part (part = position in the list) at time t and rewrites the index.
  void addStep(double time, const std::vector<std::string>& relative_files);
  const std::vector<Entry>& entries() const { return entries_; }
  const std::string& path() const { return path_; }

 private:
  std::string path_;
  std::vector<Entry> entries_;
};

}  // namespace filum::visual
