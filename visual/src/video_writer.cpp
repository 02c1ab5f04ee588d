#include "filum/visual/video_writer.hpp"

#include <stdexcept>

#include "filum/visual/offscreen_renderer.hpp"

#if FILUM_WITH_OPENCV
#include <opencv2/videoio.hpp>
#endif

namespace filum::visual {

#if FILUM_WITH_OPENCV

struct VideoWriter::Impl {
  cv::VideoWriter writer;
};

VideoWriter::VideoWriter(const std::string& path, double fps, int width, int height)
    : impl_(std::make_unique<Impl>()), path_(path), width_(width), height_(height) {
  // OpenCV's own MJPEG encoder: no FFmpeg or GStreamer codec needed.
  impl_->writer.open(path, cv::CAP_OPENCV_MJPEG, cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps,
                     cv::Size(width, height), true);
  if (!impl_->writer.isOpened())
    throw std::runtime_error(path + ": cannot open a Motion-JPEG AVI video for writing");
}

VideoWriter::~VideoWriter() { close(); }

void VideoWriter::write(const Image& frame) {
  if (frame.width != width_ || frame.height != height_)
    throw std::runtime_error(path_ + ": frame size " + std::to_string(frame.width) + "x" + std::to_string(frame.height) +
                             " differs from the video's " + std::to_string(width_) + "x" + std::to_string(height_));
  const cv::Mat mat(frame.height, frame.width, CV_8UC3, const_cast<std::uint8_t*>(frame.bgr.data()));
  impl_->writer.write(mat);
  ++frames_;
}

void VideoWriter::close() {
  if (impl_ && impl_->writer.isOpened()) impl_->writer.release();
}

#else

struct VideoWriter::Impl {};
VideoWriter::VideoWriter(const std::string&, double, int, int) { throw std::runtime_error(renderingUnavailableMessage()); }
VideoWriter::~VideoWriter() = default;
void VideoWriter::write(const Image&) {}
void VideoWriter::close() {}

#endif

}  // namespace filum::visual
