#include "filum/visual/heads_up_display.hpp"

#include <cstdio>
#include <stdexcept>

#include "filum/visual/offscreen_renderer.hpp"

#if FILUM_WITH_OPENCV
#include <opencv2/imgproc.hpp>
#endif

namespace filum::visual {

std::string headsUpText(double time, double wall_per_simulated_ms, double energy) {
  char buffer[160];
  if (wall_per_simulated_ms >= 0.0)
    std::snprintf(buffer, sizeof buffer, "t = %.3f s | %.3g ms wall per simulated ms | E = %.4g J", time,
                  wall_per_simulated_ms, energy);
  else
    std::snprintf(buffer, sizeof buffer, "t = %.3f s | E = %.4g J", time, energy);
  return buffer;
}

#if FILUM_WITH_OPENCV

namespace {

void drawBand(Image& image, const std::string& text, bool top, double scale) {
  cv::Mat mat(image.height, image.width, CV_8UC3, image.bgr.data());
  int baseline = 0;
  const double font_scale = scale * std::max(0.4, image.height / 900.0);
  const int thickness = image.height >= 700 ? 2 : 1;
  const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, font_scale, thickness, &baseline);
  const int band = size.height + baseline + 12;
  const cv::Rect rect(0, top ? 0 : image.height - band, image.width, band);
  // Darken the band (half transparent), then write in white.
  cv::Mat roi = mat(rect);
  roi.convertTo(roi, -1, 0.35, 0.0);
  cv::putText(mat, text, cv::Point(8, rect.y + 6 + size.height), cv::FONT_HERSHEY_SIMPLEX, font_scale,
              cv::Scalar(255, 255, 255), thickness, cv::LINE_AA);
}

}  // namespace

void drawHeadsUp(Image& image, const std::string& text) { drawBand(image, text, true, 0.6); }
void drawFooter(Image& image, const std::string& text) { drawBand(image, text, false, 0.45); }

#else

void drawHeadsUp(Image&, const std::string&) { throw std::runtime_error(renderingUnavailableMessage()); }
void drawFooter(Image&, const std::string&) { throw std::runtime_error(renderingUnavailableMessage()); }

#endif

}  // namespace filum::visual
