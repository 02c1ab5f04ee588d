#include "filum/visual/pvd_series.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

namespace filum::visual {

void PvdSeries::addStep(double time, const std::vector<std::string>& relative_files) {
  for (std::size_t part = 0; part < relative_files.size(); ++part)
    entries_.push_back(Entry{time, static_cast<int>(part), relative_files[part]});
  const std::string temporary = path_ + ".tmp";
  {
    std::ofstream out(temporary);
    if (!out) throw std::runtime_error(temporary + ": cannot open for writing");
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n"
        << "  <Collection>\n";
    char t[32];
    for (const Entry& e : entries_) {
      std::snprintf(t, sizeof t, "%.17g", e.time);
      out << "    <DataSet timestep=\"" << t << "\" group=\"\" part=\"" << e.part << "\" file=\"" << e.file << "\"/>\n";
    }
    out << "  </Collection>\n</VTKFile>\n";
    out.close();  // flushes: a full disk or a file size limit shows here, not in a destructor
    if (!out) throw std::runtime_error(temporary + ": write failed (disk full or file size limit?)");
  }
  if (std::rename(temporary.c_str(), path_.c_str()) != 0) throw std::runtime_error(path_ + ": cannot replace");
}

}  // namespace filum::visual
