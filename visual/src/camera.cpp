#include "filum/visual/camera.hpp"

#include <cmath>
#include <numbers>

#include "filum/core/scene_error.hpp"
#include "filum/visual/material.hpp"

namespace filum::visual {

CameraSettings CameraSettings::fromParams(const Params& p) {
  CameraSettings c;
  c.position = p.vec3({"position", "m"});
  c.look_at = p.vec3({"look_at", "m"});
  c.up = p.vec3({"up", "1"}, c.up);
  if (!((c.look_at - c.position).norm() > 0.0)) p.fail("look_at", "a point other than the camera position", "the same point");
  if (!(c.up.norm() > 0.0) || c.forward().cross(c.up.normalized()).norm() < 1e-6)
    p.fail("up", "a direction not parallel to look_at − position", "a parallel or zero vector");
  c.fov_degrees = p.positive({"fov", "°"}, c.fov_degrees);
  if (c.fov_degrees >= 170.0) p.fail("fov", "a vertical field of view in (0, 170) degrees", std::to_string(c.fov_degrees));
  if (p.has("size")) {
    const nlohmann::json& size = p.raw({"size", "px"});
    if (!size.is_array() || size.size() != 2 || !size[0].is_number_integer() || !size[1].is_number_integer() ||
        size[0].get<long>() < 16 || size[1].get<long>() < 16 || size[0].get<long>() > 8192 || size[1].get<long>() > 8192)
      p.fail("size", "[width, height] in pixels, integers in [16, 8192]", describeJson(size));
    c.width = size[0].get<int>();
    c.height = size[1].get<int>();
  }
  c.background = colorParam(p, "background", c.background);
  if (p.has("lights")) {
    for (const Params& light : p.objects("lights")) {
      Light l;
      l.position = light.vec3({"position", "m"});
      l.color = colorParam(light, "color", l.color);
      light.finish();
      c.lights.push_back(l);
    }
  }
  c.frame_interval = p.positive({"frame_interval", "s"}, c.frame_interval);
  c.heads_up = p.boolean("heads_up", c.heads_up);
  p.finish();
  return c;
}

double CameraSettings::focalPixels() const {
  return 0.5 * height / std::tan(0.5 * fov_degrees * std::numbers::pi / 180.0);
}

std::optional<CameraSettings> readCamera(const nlohmann::json& document, const std::string& source) {
  if (!document.is_object() || !document.contains("camera")) return std::nullopt;
  const Params top(document, source, "");
  return CameraSettings::fromParams(top.object("camera").withOwner("camera"));
}

CameraSettings frameBox(const Vec3& lower, const Vec3& upper, const CameraSettings& base) {
  CameraSettings c = base;
  const Vec3 center = 0.5 * (lower + upper);
  const double radius = std::max(0.5 * (upper - lower).norm(), 1e-6);
  // From the front (−y), a little to the right and above; far enough that the bounding sphere
  // fits the narrower of the two fields of view with a 10 % margin.
  const Vec3 direction = Vec3(0.35, -1.0, 0.45).normalized();
  const double half_vertical = 0.5 * c.fov_degrees * std::numbers::pi / 180.0;
  const double half_horizontal = std::atan(std::tan(half_vertical) * c.width / c.height);
  const double distance = 1.1 * radius / std::sin(std::min(half_vertical, half_horizontal));
  c.look_at = center;
  c.position = center + distance * direction;
  c.up = Vec3::UnitZ();
  return c;
}

Pixel project(const CameraSettings& camera, const Vec3& x) {
  const Vec3 d = x - camera.position;
  const double f = camera.focalPixels();
  Pixel p;
  p.depth = d.dot(camera.forward());
  p.u = 0.5 * camera.width + f * d.dot(camera.right()) / p.depth;
  p.v = 0.5 * camera.height + f * d.dot(camera.down()) / p.depth;
  return p;
}

Vec3 unproject(const CameraSettings& camera, double u, double v, double depth) {
  const double f = camera.focalPixels();
  return camera.position + depth * (camera.forward() + (u - 0.5 * camera.width) / f * camera.right() +
                                    (v - 0.5 * camera.height) / f * camera.down());
}

}  // namespace filum::visual
