// libFuzzer target: a scene file through everything `filum check` reads (the JSON with its
// shape checks, every component, the output block, the camera, the visual models, the haptics
// block), the path a user's scene takes before a run. Each input is written as scene.json into a
// scratch folder whose data/ is the reference scenes' data/, so inputs that name the reference
// meshes and curves (apps/scenes/data) read them as a scene would.
//
// Contract checked: any input ends in "ok" or an error message; a crash, a sanitizer report, a
// hang (libFuzzer's -timeout) or an allocation beyond -rss_limit_mb is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include "filum/check_command.hpp"

namespace {

/// The scratch folder of this process (the scene file and a link to the reference data), removed
/// when the fuzzer exits.
std::filesystem::path& scratchFolder() {
  static std::filesystem::path folder;
  return folder;
}

void removeScratchFolder() {
  std::error_code ignored;
  std::filesystem::remove_all(scratchFolder(), ignored);
}

std::filesystem::path scratchScene() {
  namespace fs = std::filesystem;
  static const fs::path path = [] {
    scratchFolder() = fs::temp_directory_path() / ("filum_fuzz_scene_" + std::to_string(::getpid()));
    fs::create_directories(scratchFolder());
    std::atexit(removeScratchFolder);
    std::error_code ignored;
    fs::create_directory_symlink(fs::path(FILUM_SOURCE_DIR) / "apps" / "scenes" / "data", scratchFolder() / "data",
                                 ignored);
    return scratchFolder() / "scene.json";
  }();
  return path;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path path = scratchScene();
  {
    std::ofstream file(path, std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  std::ostringstream messages;
  filum::app::checkScene(path.string(), messages);
  return 0;
}
