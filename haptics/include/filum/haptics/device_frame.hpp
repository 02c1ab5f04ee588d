// DeviceFrame: from the device's frame and units to the scene's, and back for forces.
//   x_scene = offset + scale R x_device,   v_scene = scale R v_device,
//   F_device = force_scale Rᵀ F_scene.
// R is a rotation (a Phantom's frame has y up and z toward the user; a scene's gravity is along
// −z: R = [[1,0,0],[0,0,−1],[0,1,0]] maps one onto the other), scale stretches the device's
// workspace over the scene (a 16 cm reach over a 10 cm suture field: 0.6), force_scale what the
// hand feels per newton of the scene. A spring K_scene (∂F_scene/∂x_scene) is felt as
//   K_device = force_scale · scale · Rᵀ K_scene R,
// the figure the passivity condition and the device's stiffness limit apply to (coupling.hpp).
#pragma once

#include <Eigen/Core>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"

namespace filum::haptics {

struct DeviceFrame {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();  // device axes in the scene
  double scale = 1.0;        // scene metres per device metre
  Vec3 offset = Vec3::Zero();  // scene position of the device's origin (m)
  double force_scale = 1.0;  // device newtons per scene newton

  Vec3 positionToScene(const Vec3& x) const { return offset + scale * (rotation * x); }
  Vec3 velocityToScene(const Vec3& v) const { return scale * (rotation * v); }
  Vec3 forceToDevice(const Vec3& f) const { return force_scale * (rotation.transpose() * f); }
  /// ∂F_device/∂x_device of a scene-side ∂F_scene/∂x_scene (stiffness, or damping for velocities).
  Eigen::Matrix3d gainToDevice(const Eigen::Matrix3d& g) const {
    return force_scale * scale * (rotation.transpose() * g * rotation);
  }
};

/// Reads "rotation" (3 rows of 3, orthonormal with determinant 1, or the name "y_up": a
/// Phantom's y-up frame onto a z-up scene), "scale", "offset", "force_scale". Throws SceneError
/// at the faulty key.
DeviceFrame deviceFrameFromParams(const Params& p);

}  // namespace filum::haptics
