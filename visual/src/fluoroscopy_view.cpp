#include "filum/visual/fluoroscopy_view.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Geometry>

namespace filum::visual {

namespace {
constexpr double kDegree = std::numbers::pi / 180.0;
}  // namespace

std::optional<FluoroscopyView> FluoroscopyView::fromScene(const nlohmann::json& document, const std::string& source) {
  if (!document.is_object() || !document.contains("fluoroscopy")) return std::nullopt;
  return fromParams(Params(document, source, "").object("fluoroscopy").withOwner("fluoroscopy"));
}

FluoroscopyView FluoroscopyView::fromParams(const Params& p) {
  FluoroscopyView v;
  v.lao_degrees = p.number({"lao", "°"}, v.lao_degrees);
  if (std::abs(v.lao_degrees) > 120.0) p.fail("lao", "an LAO angle in [−120, 120] degrees (negative: RAO)", std::to_string(v.lao_degrees));
  v.cranial_degrees = p.number({"cranial", "°"}, v.cranial_degrees);
  if (std::abs(v.cranial_degrees) > 60.0)
    p.fail("cranial", "a cranial angle in [−60, 60] degrees (negative: caudal)", std::to_string(v.cranial_degrees));
  if (p.has("isocenter")) v.isocenter = p.vec3({"isocenter", "m"});
  v.source_isocenter = p.positive({"source_isocenter", "m"}, v.source_isocenter);
  v.source_detector = p.positive({"source_detector", "m"}, v.source_detector);
  if (!(v.source_detector > v.source_isocenter))
    p.fail("source_detector", "a source-detector distance beyond the source-isocentre one (" + std::to_string(v.source_isocenter) + " m)",
           std::to_string(v.source_detector));
  v.field = p.positive({"field", "m"}, v.field);
  if (v.field >= 2.0 * v.source_detector) p.fail("field", "a field narrower than twice the source-detector distance", std::to_string(v.field));
  v.size = p.integer("size", 16, 4096, v.size, "pixels a side");
  v.noise = p.nonNegative({"noise", "1"}, v.noise);
  if (v.noise > 0.5) p.fail("noise", "a noise σ in [0, 0.5] of full scale", std::to_string(v.noise));
  v.frame_interval = p.positive({"frame_interval", "s"}, v.frame_interval);
  const Vec3 left = p.vec3({"left", "1"}, v.left), posterior = p.vec3({"posterior", "1"}, v.posterior);
  if (!(left.norm() > 0.0) || !(posterior.norm() > 0.0) || std::abs(left.normalized().dot(posterior.normalized())) > 1e-6)
    p.fail("posterior", "the patient's posterior direction, square to \"left\"", "a zero or oblique vector");
  v.left = left.normalized();
  v.posterior = posterior.normalized();
  if (p.has("on")) p.raw({"on", "s"});  // the pedal's (haptics/fluoroscopy_pedal.hpp), checked there
  p.finish();
  return v;
}

Vec3 FluoroscopyView::detectorDirection() const {
  const double a = lao_degrees * kDegree, b = cranial_degrees * kDegree;
  return std::cos(b) * (std::cos(a) * anterior() + std::sin(a) * left) + std::sin(b) * superior();
}

CameraSettings FluoroscopyView::camera(const Vec3& isocenter) const {
  CameraSettings c;
  const Vec3 d = detectorDirection();
  c.position = isocenter - source_isocenter * d;
  c.look_at = isocenter;
  // Head up: the superior axis square to d (at |β| <= 60° it is never parallel to d).
  c.up = (superior() - superior().dot(d) * d).normalized();
  c.fov_degrees = 2.0 * std::atan(0.5 * field / source_detector) / kDegree;
  c.width = c.height = size;
  c.background = Vec3::Ones();
  c.frame_interval = frame_interval;
  return c;
}

Pixel FluoroscopyView::project(const Vec3& isocenter, const Vec3& x) const {
  Pixel pixel = visual::project(camera(isocenter), x);
  pixel.u = size - pixel.u;  // mirrored: read from the detector's side
  return pixel;
}

Image FluoroscopyView::finish(const Image& rendered, int frame) const {
  Image out(rendered.width, rendered.height);
  std::mt19937 rng(static_cast<std::uint32_t>(frame) * 2654435761u + 1u);
  std::normal_distribution<double> gauss(0.0, noise);
  const double cx = 0.5 * rendered.width, cy = 0.5 * rendered.height, radius = 0.5 * std::min(rendered.width, rendered.height);
  for (int y = 0; y < rendered.height; ++y)
    for (int x = 0; x < rendered.width; ++x) {
      const double r = std::hypot(x + 0.5 - cx, y + 0.5 - cy) / radius;
      const double n = gauss(rng);  // drawn for every pixel, inside or not: the sequence is the frame's
      std::uint8_t grey = 0;
      if (r <= 1.0) {
        const auto bgr = rendered.at(rendered.width - 1 - x, y);  // mirrored
        const double level = (0.114 * bgr[0] + 0.587 * bgr[1] + 0.299 * bgr[2]) / 255.0;
        const double vignette = 1.0 - 0.3 * r * r;
        grey = static_cast<std::uint8_t>(std::lround(255.0 * std::clamp(level * vignette + n, 0.0, 1.0)));
      }
      const std::size_t i = 3 * (static_cast<std::size_t>(y) * out.width + x);
      out.bgr[i] = out.bgr[i + 1] = out.bgr[i + 2] = grey;
    }
  return out;
}

}  // namespace filum::visual
