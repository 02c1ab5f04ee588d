// ContactSheet: one PNG with a grid of frames of a run (left to right, top to bottom, each
// labelled with its time), for a quick look without playing the video.
#pragma once

#include <string>
#include <vector>

#include "filum/visual/image.hpp"

namespace filum::visual {

class ContactSheet {
 public:
  /// columns >= 1; thumbnails `thumbnail_width` pixels wide (height keeps the aspect ratio).
  explicit ContactSheet(int columns = 4, int thumbnail_width = 400, std::string title = "");

  /// Adds a downscaled copy of the frame with its label (e.g. "t = 0.50 s").
  void add(const Image& frame, const std::string& label);
  /// Replaces the last thumbnail (used to end the sheet on the final frame).
  void replaceLast(const Image& frame, const std::string& label);
  int count() const { return static_cast<int>(thumbnails_.size()); }

  /// The grid (rows = ceil(count / columns)), white gaps, the title on top.
  Image compose() const;
  /// Writes compose() as PNG. Throws std::runtime_error.
  void write(const std::string& path) const;

 private:
  int columns_, thumbnail_width_;
  std::string title_;
  std::vector<Image> thumbnails_;
};

/// The indices of `picks` frames spread evenly over frames 0 .. total − 1 (first and last
/// included; all of them if total <= picks).
std::vector<int> contactSheetPicks(int total, int picks);

}  // namespace filum::visual
