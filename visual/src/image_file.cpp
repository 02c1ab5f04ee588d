#include "filum/visual/image_file.hpp"

#include <cstring>
#include <stdexcept>

#include "filum/visual/offscreen_renderer.hpp"

#if FILUM_WITH_OPENCV
#include <opencv2/imgcodecs.hpp>
#endif

namespace filum::visual {

#if FILUM_WITH_OPENCV

void writePng(const std::string& path, const Image& image) {
  const cv::Mat mat(image.height, image.width, CV_8UC3, const_cast<std::uint8_t*>(image.bgr.data()));
  if (!cv::imwrite(path, mat)) throw std::runtime_error(path + ": cannot write the PNG file");
}

Image readPng(const std::string& path) {
  const cv::Mat mat = cv::imread(path, cv::IMREAD_COLOR);
  if (mat.empty()) throw std::runtime_error(path + ": cannot read the picture");
  Image image(mat.cols, mat.rows);
  for (int y = 0; y < mat.rows; ++y)
    std::memcpy(image.bgr.data() + 3 * static_cast<std::size_t>(y) * mat.cols, mat.ptr(y), 3 * mat.cols);
  return image;
}

#else

void writePng(const std::string&, const Image&) { throw std::runtime_error(renderingUnavailableMessage()); }
Image readPng(const std::string&) { throw std::runtime_error(renderingUnavailableMessage()); }

#endif

}  // namespace filum::visual
