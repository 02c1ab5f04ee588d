// The heads-up line drawn on rendered frames: simulated time, wall time per simulated
// millisecond (≤ 1 is real time) and energy, on a dark band at the top of the picture.
#pragma once

#include <string>

#include "filum/visual/image.hpp"

namespace filum::visual {

/// "t = 0.533 s | 0.171 ms wall per simulated ms | E = 1.23e-05 J" (wall time omitted if < 0).
std::string headsUpText(double time, double wall_per_simulated_ms, double energy);

/// Draws `text` on a band across the top of the image (OpenCV imgproc). Throws std::runtime_error
/// without OpenCV.
void drawHeadsUp(Image& image, const std::string& text);

/// Draws `text` at the bottom-left corner (a smaller label, e.g. the keys of the viewer).
void drawFooter(Image& image, const std::string& text);

}  // namespace filum::visual
