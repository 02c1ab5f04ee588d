#include "filum/visual/contact_sheet.hpp"

#include <cmath>
#include <cstring>
#include <stdexcept>

#include "filum/visual/image_file.hpp"
#include "filum/visual/offscreen_renderer.hpp"

#if FILUM_WITH_OPENCV
#include <opencv2/imgproc.hpp>
#endif

namespace filum::visual {

std::vector<int> contactSheetPicks(int total, int picks) {
  std::vector<int> out;
  if (total <= 0 || picks <= 0) return out;
  if (total <= picks) {
    for (int i = 0; i < total; ++i) out.push_back(i);
    return out;
  }
  for (int k = 0; k < picks; ++k) {
    const int i = static_cast<int>(std::lround(static_cast<double>(k) * (total - 1) / (picks - 1)));
    if (out.empty() || i != out.back()) out.push_back(i);
  }
  return out;
}

ContactSheet::ContactSheet(int columns, int thumbnail_width, std::string title)
    : columns_(std::max(1, columns)), thumbnail_width_(std::max(16, thumbnail_width)), title_(std::move(title)) {}

#if FILUM_WITH_OPENCV

namespace {

Image thumbnail(const Image& frame, int width, const std::string& label) {
  const cv::Mat source(frame.height, frame.width, CV_8UC3, const_cast<std::uint8_t*>(frame.bgr.data()));
  const int height = std::max(1, static_cast<int>(std::lround(static_cast<double>(width) * frame.height / frame.width)));
  Image small(width, height);
  cv::Mat target(height, width, CV_8UC3, small.bgr.data());
  cv::resize(source, target, target.size(), 0, 0, cv::INTER_AREA);
  // The label in a white box at the bottom left.
  int baseline = 0;
  const cv::Size size = cv::getTextSize(label, cv::FONT_HERSHEY_SIMPLEX, 0.5, 1, &baseline);
  cv::rectangle(target, cv::Rect(0, height - size.height - baseline - 8, size.width + 12, size.height + baseline + 8),
                cv::Scalar(255, 255, 255), cv::FILLED);
  cv::putText(target, label, cv::Point(6, height - baseline - 4), cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1,
              cv::LINE_AA);
  return small;
}

}  // namespace

void ContactSheet::add(const Image& frame, const std::string& label) {
  thumbnails_.push_back(thumbnail(frame, thumbnail_width_, label));
}

void ContactSheet::replaceLast(const Image& frame, const std::string& label) {
  if (thumbnails_.empty())
    add(frame, label);
  else
    thumbnails_.back() = thumbnail(frame, thumbnail_width_, label);
}

Image ContactSheet::compose() const {
  if (thumbnails_.empty()) throw std::runtime_error("contact sheet: no frames");
  const int gap = 6, title_height = title_.empty() ? 0 : 34;
  const int w = thumbnails_.front().width, h = thumbnails_.front().height;
  const int count = static_cast<int>(thumbnails_.size());
  const int columns = std::min(columns_, count), rows = (count + columns - 1) / columns;
  Image sheet(gap + columns * (w + gap), title_height + gap + rows * (h + gap));
  cv::Mat mat(sheet.height, sheet.width, CV_8UC3, sheet.bgr.data());
  mat.setTo(cv::Scalar(255, 255, 255));
  if (!title_.empty())
    cv::putText(mat, title_, cv::Point(gap + 2, 24), cv::FONT_HERSHEY_SIMPLEX, 0.7, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  for (int i = 0; i < count; ++i) {
    const Image& t = thumbnails_[i];
    const cv::Mat tile(t.height, t.width, CV_8UC3, const_cast<std::uint8_t*>(t.bgr.data()));
    tile.copyTo(mat(cv::Rect(gap + (i % columns) * (w + gap), title_height + gap + (i / columns) * (h + gap), t.width,
                             t.height)));
  }
  return sheet;
}

#else

void ContactSheet::add(const Image&, const std::string&) { throw std::runtime_error(renderingUnavailableMessage()); }
void ContactSheet::replaceLast(const Image&, const std::string&) { throw std::runtime_error(renderingUnavailableMessage()); }
Image ContactSheet::compose() const { throw std::runtime_error(renderingUnavailableMessage()); }

#endif

void ContactSheet::write(const std::string& path) const { writePng(path, compose()); }

}  // namespace filum::visual
