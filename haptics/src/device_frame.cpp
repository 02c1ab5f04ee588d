#include "filum/haptics/device_frame.hpp"

#include <cmath>

#include <Eigen/LU>  // determinant

#include "filum/core/scene_error.hpp"

namespace filum::haptics {

namespace {

// Orthonormality to round-off: the rows are typed with about 16 digits, so RᵀR − I is of order
// 1e-16 per entry for an exact rotation; 1e-9 still accepts rows typed to 9 digits.
constexpr double kRotationTolerance = 1e-9;

Eigen::Matrix3d rotationFromRows(const Params& p, const nlohmann::json& rows) {
  if (!rows.is_array() || rows.size() != 3) p.fail("rotation", "3 rows of 3 numbers, or \"y_up\"");
  Eigen::Matrix3d R;
  for (int i = 0; i < 3; ++i) {
    const auto& row = rows[i];
    if (!row.is_array() || row.size() != 3) p.fail("rotation", "3 rows of 3 numbers, or \"y_up\"");
    for (int j = 0; j < 3; ++j) {
      if (!row[j].is_number() || !std::isfinite(row[j].get<double>())) p.fail("rotation", "3 rows of 3 finite numbers");
      R(i, j) = row[j].get<double>();
    }
  }
  if ((R.transpose() * R - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff() > kRotationTolerance ||
      std::abs(R.determinant() - 1.0) > kRotationTolerance)
    p.fail("rotation", "a rotation (orthonormal rows, determinant 1)");
  return R;
}

}  // namespace

DeviceFrame deviceFrameFromParams(const Params& p) {
  DeviceFrame f;
  if (p.has("rotation")) {
    const nlohmann::json& r = p.raw({"rotation", "1"});
    if (r.is_string()) {
      if (r.get<std::string>() != "y_up") p.fail("rotation", "3 rows of 3 numbers, or \"y_up\"");
      f.rotation << 1, 0, 0, 0, 0, -1, 0, 1, 0;
    } else {
      f.rotation = rotationFromRows(p, r);
    }
  }
  f.scale = p.positive({"scale", "1"}, f.scale);
  f.offset = p.vec3({"offset", "m"}, f.offset);
  f.force_scale = p.positive({"force_scale", "1"}, f.force_scale);
  return f;
}

}  // namespace filum::haptics
