#include "filum/core/input_file.hpp"

#include <cstdio>
#include <filesystem>
#include <system_error>

namespace filum {

namespace fs = std::filesystem;

std::string byteSize(std::uintmax_t bytes) {
  char text[32];
  if (bytes < 1024) return std::to_string(bytes) + " bytes";
  const double kib = static_cast<double>(bytes) / 1024.0;
  if (kib < 1024.0) std::snprintf(text, sizeof text, "%.1f KiB", kib);
  else if (kib < 1024.0 * 1024.0) std::snprintf(text, sizeof text, "%.1f MiB", kib / 1024.0);
  else std::snprintf(text, sizeof text, "%.1f GiB", kib / (1024.0 * 1024.0));
  return text;
}

std::string inputFileProblem(const std::string& path, std::uintmax_t max_bytes) {
  std::error_code error;
  const fs::file_status status = fs::status(path, error);  // follows symbolic links
  if (error || !fs::exists(status)) return "no such file";
  switch (status.type()) {
    case fs::file_type::regular: break;
    case fs::file_type::directory: return "a directory";
    case fs::file_type::fifo: return "a FIFO (named pipe), which would block";
    case fs::file_type::socket: return "a socket";
    case fs::file_type::character:
    case fs::file_type::block: return "a device file, which may never end";
    default: return "not a regular file";
  }
  const std::uintmax_t size = fs::file_size(path, error);
  if (error) return "a file whose size cannot be read (" + error.message() + ")";
  if (size > max_bytes) return "a file of " + byteSize(size) + ", more than the limit of " + byteSize(max_bytes);
  return "";
}

std::uintmax_t inputFileSize(const std::string& path) {
  std::error_code error;
  const std::uintmax_t size = fs::file_size(path, error);
  return error ? 0 : size;
}

}  // namespace filum
