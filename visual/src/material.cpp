#include "filum/visual/material.hpp"

namespace filum::visual {

Vec3 colorParam(const Params& p, const std::string& key, const Vec3& fallback) {
  const Vec3 c = p.vec3({key, "1"}, fallback);  // red, green, blue in [0, 1]
  if ((c.array() < 0.0).any() || (c.array() > 1.0).any()) {
    // Appended piece by piece: GCC 12 sees a false overlap (-Wrestrict) in "[" + temporary.
    std::string found = "[";
    found += std::to_string(c.x());
    found += ", ";
    found += std::to_string(c.y());
    found += ", ";
    found += std::to_string(c.z());
    found += ']';
    p.fail(key, "an [r, g, b] colour with components in [0, 1]", found);
  }
  return c;
}

Material Material::fromParams(const Params& p, const Material& fallback) {
  Material m;
  m.color = colorParam(p, "color", fallback.color);
  m.opacity = p.positive({"opacity", "1"}, fallback.opacity);
  if (m.opacity > 1.0) p.fail("opacity", "an opacity in (0, 1]", std::to_string(m.opacity));
  m.xray_opacity = fallback.xray_opacity;
  if (p.has("xray_opacity")) {
    m.xray_opacity = p.nonNegative({"xray_opacity", "1"}, 0.0);
    if (m.xray_opacity > 1.0) p.fail("xray_opacity", "an X-ray opacity in [0, 1]", std::to_string(m.xray_opacity));
  }
  return m;
}

}  // namespace filum::visual
