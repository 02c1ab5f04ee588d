// Input files (scene files, mesh files): checked before a byte is read. A FIFO, a socket or a
// device such as /dev/zero would block or never end, and a file far larger than any real input
// would exhaust memory once parsed, so both are refused with what was found.
#pragma once

#include <cstdint>
#include <string>

namespace filum {

/// "" when `path` names a regular file (symbolic links followed) of at most `max_bytes`;
/// otherwise what was found instead ("a FIFO (named pipe)", "a directory", "12 GB", ...).
std::string inputFileProblem(const std::string& path, std::uintmax_t max_bytes);

/// The size of a file that inputFileProblem accepted (bytes).
std::uintmax_t inputFileSize(const std::string& path);

/// Mesh files (.obj, .off, .ply, .stl, .vtp), at most: 256 MiB is a mesh of several million
/// triangles, beyond what a step's collision queries or a frame's drawing can use. The counts a
/// mesh header announces are checked against the bytes by the reader itself
/// (geometry/mesh_file.hpp), before it allocates for them.
inline constexpr std::uintmax_t kMaxMeshFileBytes = 256u << 20;

/// "12.0 MiB" for messages.
std::string byteSize(std::uintmax_t bytes);

}  // namespace filum
