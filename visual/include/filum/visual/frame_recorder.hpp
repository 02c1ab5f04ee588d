// FrameRecorder: what a rendered run writes — every frame as frames/frame_NNNNNN.png, a
// Motion-JPEG video (video.avi, 1 / frame_interval frames per second: real-time playback) and a
// contact sheet (contact_sheet.png, 12 frames spread over the run, the last one always
// included, so a run that stops early still ends on its last frame).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "filum/visual/contact_sheet.hpp"
#include "filum/visual/image.hpp"
#include "filum/visual/video_writer.hpp"

namespace filum::visual {

struct FrameRecorderOptions {
  std::string directory;      // frames/, video.avi and contact_sheet.png go here
  double fps = 30.0;          // video frame rate
  int expected_frames = 0;    // for spreading the contact sheet's picks
  int sheet_frames = 12;
  int sheet_columns = 4;
  bool png_frames = true;
  std::string title;          // contact sheet title (the scene name)
};

class FrameRecorder {
 public:
  /// Creates the directories. Throws std::runtime_error (also without OpenCV).
  explicit FrameRecorder(FrameRecorderOptions options);
  ~FrameRecorder();

  /// Records the next frame, rendered at simulated time t (s).
  void add(const Image& frame, double time);
  /// Closes the video and writes the contact sheet (idempotent).
  void finish();
  int frames() const { return frames_; }
  std::string videoPath() const { return options_.directory + "/video.avi"; }
  std::string sheetPath() const { return options_.directory + "/contact_sheet.png"; }

 private:
  FrameRecorderOptions options_;
  std::unique_ptr<VideoWriter> video_;
  ContactSheet sheet_;
  std::vector<int> picks_;
  std::size_t next_pick_ = 0;
  Image last_;
  double last_time_ = 0.0;
  int frames_ = 0;
  bool last_in_sheet_ = false, finished_ = false;
};

}  // namespace filum::visual
