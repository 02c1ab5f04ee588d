// `filum run` from a test: a fresh output folder and one call of runScene with its log.
#pragma once

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "filum/run_command.hpp"

namespace filum::test {

/// The bytes of a file ("" when it cannot be read).
inline std::string readAll(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

/// build/test_output/<name>, emptied.
inline std::filesystem::path freshDirectory(const std::string& name) {
  const std::filesystem::path dir = std::filesystem::path(FILUM_BINARY_DIR) / "test_output" / name;
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

/// Runs `scene` for `duration` s (0: the scene's own) into `out`, without progress lines;
/// returns the exit status of `filum run` and its messages in `log`.
inline int runQuietly(const std::filesystem::path& scene, const std::filesystem::path& out, double duration,
                    std::string& log) {
  app::RunOptions options;
  options.scene = scene.string();
  options.out = out.string();
  options.duration = duration;
  options.progress = false;
  std::ostringstream log_stream, progress;
  const int status = app::runScene(options, log_stream, progress);
  log = log_stream.str();
  return status;
}

}  // namespace filum::test
