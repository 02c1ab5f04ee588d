// The scene file's "output" block, read by `filum run` and checked by `filum check`:
//   "output": {"interval": 0.01, "curve_samples": 64, "knots": true}
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace filum::app {

/// Points per curve in curve.csv and the .vtp files: at most 100,000. A frame holds
/// curve_samples × bodies lines of about 100 bytes, so the limit is 10 MB per body and frame
/// (and the same bound as `filum run --samples`).
inline constexpr int kMaxCurveSamples = 100000;

struct OutputSettings {
  double interval = 0.01;  // simulated seconds between frames
  int curve_samples = 64;  // points per curve
  bool knots = true;       // knot.csv: the knot type of every thread's strands per frame
};

/// Reads and checks the block (absent: the defaults). Throws SceneError naming the place.
OutputSettings readOutputSettings(const nlohmann::json& document, const std::string& source);

}  // namespace filum::app
