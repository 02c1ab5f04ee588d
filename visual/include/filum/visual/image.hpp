// Image: an 8-bit BGR picture (the renderers' output, the PNG frames, the video frames), kept
// free of OpenCV types so that the public headers do not depend on it (FILUM_WITH_OPENCV).
#pragma once

#include <array>
#include <cstdint>
#include <vector>

namespace filum::visual {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> bgr;  // row-major, 3 bytes per pixel (blue, green, red)

  Image() = default;
  Image(int w, int h) : width(w), height(h), bgr(static_cast<std::size_t>(3) * w * h, 0) {}
  bool empty() const { return width == 0 || height == 0; }
  /// {b, g, r} of pixel (x right, y down).
  std::array<std::uint8_t, 3> at(int x, int y) const {
    const std::size_t i = 3 * (static_cast<std::size_t>(y) * width + x);
    return {bgr[i], bgr[i + 1], bgr[i + 2]};
  }
};

}  // namespace filum::visual
