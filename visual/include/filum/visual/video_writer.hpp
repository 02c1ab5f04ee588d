// VideoWriter: a video file of rendered frames through cv::VideoWriter, Motion-JPEG in an AVI
// container — OpenCV's built-in encoder (CAP_OPENCV_MJPEG), present in every Debian OpenCV build
// without FFmpeg codecs or downloads; players (VLC, mpv, ffplay, browsers via ffmpeg) read it.
#pragma once

#include <memory>
#include <string>

#include "filum/visual/image.hpp"

namespace filum::visual {

class VideoWriter {
 public:
  /// path should end in .avi; fps > 0; every frame must be width × height. Throws
  /// std::runtime_error if the file cannot be opened or this build has no OpenCV.
  VideoWriter(const std::string& path, double fps, int width, int height);
  ~VideoWriter();
  void write(const Image& frame);
  /// Finishes the file (also done by the destructor).
  void close();
  int frames() const { return frames_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::string path_;
  int width_, height_, frames_ = 0;
};

}  // namespace filum::visual
