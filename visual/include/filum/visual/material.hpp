// Material: how a visual model is drawn — its colour and opacity — read from the scene file
// ("color": [r, g, b] with components in [0, 1], "opacity": in (0, 1]), and in the fluoroscopy
// view ("xray_opacity": in [0, 1], the fraction of X-rays one layer of it stops; default: the
// model's kind's, VisualModel::defaultXrayOpacity).
#pragma once

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::visual {

struct Material {
  Vec3 color{0.8, 0.8, 0.8};  // linear RGB in [0, 1]
  double opacity = 1.0;       // 1: opaque
  double xray_opacity = -1.0; // in the fluoroscopy view; < 0: the model's default

  /// Reads "color" and "opacity" (both optional, defaults from `fallback`).
  static Material fromParams(const Params& p, const Material& fallback);
};

/// An [r, g, b] colour with components in [0, 1] at p[key], or fallback if absent.
Vec3 colorParam(const Params& p, const std::string& key, const Vec3& fallback);

}  // namespace filum::visual
