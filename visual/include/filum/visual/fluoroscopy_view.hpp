// FluoroscopyView: the picture an interventionalist steers by, a C-arm's X-ray projection.
// Geometry, with the patient's axes L (left), P (posterior), S = L × P (superior) — DICOM's LPS,
// by default the scene's x, y, z — and A = −P: the detector lies in the direction
//   d = cos β (cos α A + sin α L) + sin β S
// from the isocentre, α the LAO angle (negative: RAO), β the cranial angle (negative: caudal);
// the X-ray source opposite, at SOD from the isocentre, the detector at SID from the source. The
// picture is the central projection from the source onto the detector, read from the detector's
// side as radiographs are: an AP view (α = β = 0) shows the patient's left on the right, the head
// up. A point at depth z = (x − source)·d is magnified SID / z (SID/SOD at the isocentre).
// Tones: each layer a ray crosses transmits (1 − a) of it, a the model's X-ray opacity
// (VisualModel::xrayOpacity): I = I₀ Π_k (1 − a_k), Beer–Lambert's exp(−Σ μ_k t_k) for layers of
// fixed thickness; a black, unlit, translucent surface drawn over white composites exactly so.
// Instruments are near opaque, contrast-filled vessels faint, soft tissue fainter, tables and
// markers not seen. Then the image intensifier: grey, a circular field (black outside), a
// vignette (brightness falling to 70 % at the rim), and quantum noise (Gaussian, σ = "noise" of
// full scale, seeded by the frame's number: the same run gives the same pictures). While the
// pedal is up (haptics/fluoroscopy_pedal.hpp) the monitor holds the last image.
// Scene, the top-level block (its "on" spans are the pedal's):
//   "fluoroscopy": {"lao": 30, "cranial": 0,                  // degrees, in [−120, 120] and [−60, 60]
//                   "isocenter": [x, y, z],                   // m; default: the middle of the models
//                   "source_isocenter": 0.75, "source_detector": 1.05,   // m: SOD < SID
//                   "field": 0.3,                             // m: the detector field's diameter
//                   "size": 720, "noise": 0.02, "frame_interval": 0.0667,  // px, of full scale, s
//                   "left": [1, 0, 0], "posterior": [0, 1, 0]} // the patient's axes in the scene
#pragma once

#include <optional>
#include <string>

#include <nlohmann/json.hpp>

#include "filum/core/params.hpp"
#include "filum/core/types.hpp"
#include "filum/visual/camera.hpp"
#include "filum/visual/image.hpp"

namespace filum::visual {

struct FluoroscopyView {
  double lao_degrees = 0.0, cranial_degrees = 0.0;
  std::optional<Vec3> isocenter;        // m; nullopt: the middle of the framed models
  double source_isocenter = 0.75;       // m (SOD)
  double source_detector = 1.05;        // m (SID)
  double field = 0.3;                   // m, diameter of the detector's field
  int size = 720;                       // pixels, square
  double noise = 0.02;                  // σ of the quantum noise, of full scale
  double frame_interval = 1.0 / 15.0;   // s of simulated time between pictures (15 pulses/s)
  Vec3 left = Vec3::UnitX(), posterior = Vec3::UnitY();

  /// The scene's "fluoroscopy" block, or nullopt without one. Throws SceneError naming the place.
  static std::optional<FluoroscopyView> fromScene(const nlohmann::json& document, const std::string& source);
  static FluoroscopyView fromParams(const Params& p);

  Vec3 superior() const { return left.cross(posterior); }
  Vec3 anterior() const { return -posterior; }
  /// d: from the isocentre towards the detector.
  Vec3 detectorDirection() const;
  /// The camera at the source, looking at the isocentre, head up, its field the detector's.
  /// The picture it renders is mirrored left to right by finish() (read from the detector side).
  CameraSettings camera(const Vec3& isocenter) const;
  /// The pixel of x in the finished picture (the camera's projection, mirrored).
  Pixel project(const Vec3& isocenter, const Vec3& x) const;
  /// The rendered picture made a fluoroscopic one: mirrored, grey, the round field, vignette and
  /// noise (seeded by `frame`).
  Image finish(const Image& rendered, int frame) const;
};

}  // namespace filum::visual
