// The result rows of a study run one configuration at a time (`--configuration K` prints the
// row "K,..."; a sweep gathers them, python/filum_sweeps) and read back by `--rows FILE`: every
// configuration once, in any order. Shared by accuracy_pareto and stability_map.
#pragma once

#include <cstddef>
#include <fstream>
#include <iostream>
#include <optional>
#include <string>
#include <vector>

namespace filum::bench {

/// Reads the rows of `path` into rows[K] (rows.size() configurations). parse(line, K, row)
/// returns false for a malformed line. A malformed row, a K out of range or a configuration
/// without a row is reported on stderr with the file and line (`expected` describes a row,
/// `program` names the study for its --list) and returns false.
template <typename Row, typename Parse>
bool readIndexedRows(const std::string& path, std::vector<std::optional<Row>>& rows, Parse parse,
                     const std::string& expected, const std::string& program) {
  std::ifstream in(path);
  if (!in) {
    std::cerr << path << ": cannot read the result rows\n";
    return false;
  }
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    if (line.empty()) continue;
    std::size_t index = 0;
    Row row;
    if (!parse(line, index, row) || index >= rows.size()) {
      std::cerr << path << ":" << number << ": expected a row '" << expected << "' with K < " << rows.size()
                << ", found '" << line << "'\n";
      return false;
    }
    rows[index] = row;
  }
  for (std::size_t k = 0; k < rows.size(); ++k)
    if (!rows[k]) {
      std::cerr << path << ": no row for configuration " << k << " (" << program << " --list)\n";
      return false;
    }
  return true;
}

}  // namespace filum::bench
