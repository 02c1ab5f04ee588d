// PNG files of rendered frames (OpenCV imgcodecs): write, and read back (tests, tools).
#pragma once

#include <string>

#include "filum/visual/image.hpp"

namespace filum::visual {

/// Throws std::runtime_error if the file cannot be written or this build has no OpenCV.
void writePng(const std::string& path, const Image& image);
/// Throws std::runtime_error if the file cannot be read or this build has no OpenCV.
Image readPng(const std::string& path);

}  // namespace filum::visual
