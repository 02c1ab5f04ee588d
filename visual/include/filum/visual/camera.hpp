// Camera, lights and background of the pictures, from the scene file's top-level "camera" block:
//   "camera": {
//     "position": [x, y, z], "look_at": [x, y, z], "up": [0, 0, 1],   // m; up: default +z
//     "fov": 30,                  // vertical field of view (degrees)
//     "size": [960, 540],         // image width and height (pixels)
//     "background": [1, 1, 1],    // colour, components in [0, 1]
//     "lights": [{"position": [x, y, z], "color": [1, 1, 1]}],   // default: the renderer's headlight
//     "frame_interval": 0.0333,   // simulated seconds between rendered frames; the video plays
//                                 // at 1/interval fps, at most 30 (closer frames: slow motion)
//     "heads_up": true            // the line with time, wall time per simulated ms and energy
//   }
// A pinhole camera: with the camera axes right = normalize(forward × up), down = forward ×
// right, forward = normalize(look_at − position), and f = (height / 2) / tan(fov / 2), a point x
// projects to pixel (u, v) = (w/2 + f x_r / x_f, h/2 + f x_d / x_f) (u to the right, v down, as
// in images). The renderers use exactly this projection; tests check pictures against it.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>  // cross products
#include <nlohmann/json.hpp>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::visual {

struct Light {
  Vec3 position = Vec3::Zero();  // m
  Vec3 color = Vec3::Ones();     // in [0, 1]
};

struct CameraSettings {
  Vec3 position{0.0, -1.0, 0.0};  // m
  Vec3 look_at = Vec3::Zero();    // m
  Vec3 up = Vec3::UnitZ();
  double fov_degrees = 30.0;      // vertical
  int width = 960, height = 540;  // pixels
  Vec3 background{1.0, 1.0, 1.0};
  std::vector<Light> lights;      // empty: a headlight
  double frame_interval = 1.0 / 30.0;  // s of simulated time between rendered frames
  bool heads_up = true;

  /// From a "camera" object; throws SceneError naming the file and JSON path.
  static CameraSettings fromParams(const Params& p);

  Vec3 forward() const { return (look_at - position).normalized(); }
  Vec3 right() const { return forward().cross(up).normalized(); }
  Vec3 down() const { return forward().cross(right()); }
  /// Focal length in pixels.
  double focalPixels() const;
};

/// The scene file's "camera" block, or nullopt if it has none.
std::optional<CameraSettings> readCamera(const nlohmann::json& document, const std::string& source);

/// A camera that frames the box [lower, upper] from the front-right and above (z up), keeping
/// `base`'s image size, lights, background and intervals.
CameraSettings frameBox(const Vec3& lower, const Vec3& upper, const CameraSettings& base = CameraSettings());

struct Pixel {
  double u = 0.0, v = 0.0;  // pixels, u right, v down
  double depth = 0.0;       // distance along the viewing direction (m); <= 0: behind the camera
};
/// The pinhole projection described above.
Pixel project(const CameraSettings& camera, const Vec3& x);
/// The point at `depth` along the viewing direction that projects to pixel (u, v): the inverse.
Vec3 unproject(const CameraSettings& camera, double u, double v, double depth);

}  // namespace filum::visual
