#include "filum/core/input_file.hpp"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
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

namespace {

std::string lowerExtension(const std::string& path) {
  std::string extension = fs::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  return extension;
}

// "OFF V F E" (comments after '#'); the counts may follow on the same line or the next ones.
std::string offHeaderProblem(std::ifstream& in, std::uintmax_t size) {
  std::string text, line;
  for (int lines = 0; lines < 64 && std::getline(in, line); ++lines) {
    text += line.substr(0, line.find('#')) + '\n';
    std::istringstream words(text);
    std::string header;
    long long vertices = -1, faces = -1;
    if (!(words >> header >> vertices >> faces)) continue;
    if (vertices < 0 || faces < 0) return "";  // the reader says what it expected
    const auto bytes = static_cast<long double>(size);
    if (vertices * 6.0L > bytes || faces * 8.0L > bytes)
      return "a header announcing " + std::to_string(vertices) + " vertices and " + std::to_string(faces) +
             " faces in a file of " + std::to_string(size) + " bytes (a vertex takes at least 6 bytes, a face 8)";
    return "";
  }
  return "";
}

// "element <name> <count>" lines up to "end_header".
std::string plyHeaderProblem(std::ifstream& in, std::uintmax_t size) {
  std::string line;
  for (int lines = 0; lines < 1000 && std::getline(in, line); ++lines) {
    std::istringstream words(line);
    std::string tag, name;
    long long count = 0;
    words >> tag;
    if (tag == "end_header") return "";
    if (tag == "element" && (words >> name >> count) && (count < 0 || static_cast<std::uintmax_t>(count) > size))
      return "a header announcing " + std::to_string(count) + " elements '" + name + "' in a file of " +
             std::to_string(size) + " bytes (an element takes at least one byte)";
  }
  return "";
}

}  // namespace

std::string meshHeaderProblem(const std::string& path) {
  const std::string extension = lowerExtension(path);
  if (extension != ".off" && extension != ".ply") return "";
  std::ifstream in(path, std::ios::binary);
  if (!in) return "";
  const std::uintmax_t size = inputFileSize(path);
  return extension == ".off" ? offHeaderProblem(in, size) : plyHeaderProblem(in, size);
}

}  // namespace filum
