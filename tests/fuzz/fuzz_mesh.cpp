// libFuzzer target: the bytes of a mesh file through geometry's one mesh reader (readMesh, used
// by collision's TriangleMeshSurface and visual's MeshModel), in the format FILUM_FUZZ_FORMAT
// (one program per format: OBJ, OFF, PLY, STL, VTP).
//
// Contract checked: any input gives a mesh whose indices are in range and coordinates finite,
// or a std::runtime_error; a crash, a sanitizer report, a hang (-timeout) or an allocation
// beyond -rss_limit_mb is a finding.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <string_view>

#include "filum/geometry/mesh_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace filum::geometry;
  try {
    const PolygonSoup soup =
        readMesh(std::string_view(reinterpret_cast<const char*>(data), size), MeshFormat::FILUM_FUZZ_FORMAT, "fuzz");
    const long v = static_cast<long>(soup.vertices.rows());
    if (!soup.vertices.allFinite()) std::abort();  // the reader promises finite coordinates
    if (soup.triangles.size() > 0 && (soup.triangles.minCoeff() < 0 || soup.triangles.maxCoeff() >= v))
      std::abort();  // and indices in range
  } catch (const std::runtime_error&) {
    // A refusal with its place: the expected outcome for most inputs.
  }
  return 0;
}
