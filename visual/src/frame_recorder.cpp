#include "filum/visual/frame_recorder.hpp"

#include <cstdio>
#include <filesystem>

#include "filum/visual/image_file.hpp"

namespace filum::visual {

namespace {

std::string timeLabel(double t) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "t = %.3f s", t);  // ms: frames 1/30 s apart stay distinct
  return buffer;
}

}  // namespace

FrameRecorder::FrameRecorder(FrameRecorderOptions options)
    : options_(std::move(options)), sheet_(options_.sheet_columns, 400, options_.title) {
  std::filesystem::create_directories(options_.directory);
  if (options_.png_frames) std::filesystem::create_directories(options_.directory + "/frames");
  picks_ = contactSheetPicks(std::max(1, options_.expected_frames), options_.sheet_frames);
}

FrameRecorder::~FrameRecorder() {
  try {
    finish();
  } catch (...) {
    // Destructors must not throw; finish() is called explicitly by users that want errors.
  }
}

void FrameRecorder::add(const Image& frame, double time) {
  if (!video_) video_ = std::make_unique<VideoWriter>(videoPath(), options_.fps, frame.width, frame.height);
  video_->write(frame);
  if (options_.png_frames) {
    char name[48];
    std::snprintf(name, sizeof name, "/frames/frame_%06d.png", frames_);
    writePng(options_.directory + name, frame);
  }
  last_in_sheet_ = next_pick_ < picks_.size() && picks_[next_pick_] == frames_;
  if (last_in_sheet_) {
    sheet_.add(frame, timeLabel(time));
    ++next_pick_;
  }
  last_ = frame;
  last_time_ = time;
  ++frames_;
}

void FrameRecorder::finish() {
  if (finished_) return;
  finished_ = true;
  if (video_) video_->close();
  if (frames_ == 0) return;
  // End the sheet on the last frame: append it, or replace the last pick if the sheet is full.
  if (!last_in_sheet_) {
    if (sheet_.count() < options_.sheet_frames)
      sheet_.add(last_, timeLabel(last_time_));
    else
      sheet_.replaceLast(last_, timeLabel(last_time_));
  }
  sheet_.write(sheetPath());
}

}  // namespace filum::visual
