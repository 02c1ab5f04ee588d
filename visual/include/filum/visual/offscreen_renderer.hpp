// OffscreenRenderer: pictures of the visual models with OpenCV's viz module (VTK, OpenGL through
// Mesa) rendering off screen into an image, under the X display of DisplayServer (an Xvfb when
// there is no $DISPLAY). Camera, lights and background come from CameraSettings; each model is
// a cv::viz::WMesh with its smooth vertex normals (Phong shading), colour and opacity.
//
// Frames are produced by VTK's window-to-image filter (Viz3d::getScreenshot) without ever
// starting viz's interactor: Viz3d::spinOnce() re-creates the render window (dropping the
// off-screen flag) and runs the X event loop, which under Xvfb crashed intermittently in
// vtkXRenderWindowInteractor::Initialize (XSync) and raised BadWindow errors on exit in our
// trials (OpenCV 4.6, VTK 9.1, Debian 12); rendering through the filter alone never failed.
//
// Needs FILUM_WITH_OPENCV=ON; otherwise the constructor throws a std::runtime_error naming it.
#pragma once

#include <memory>
#include <vector>

#include "filum/visual/camera.hpp"
#include "filum/visual/image.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

/// True if this build renders pictures (FILUM_WITH_OPENCV=ON).
bool renderingAvailable();

/// The message of the error raised when rendering was built out.
const char* renderingUnavailableMessage();

class OffscreenRenderer {
 public:
  /// Opens the renderer (and the display). Throws std::runtime_error if this build has no
  /// OpenCV (FILUM_WITH_OPENCV=OFF) or no X display can be had (see DisplayServer).
  explicit OffscreenRenderer(const CameraSettings& camera);
  ~OffscreenRenderer();
  OffscreenRenderer(const OffscreenRenderer&) = delete;
  OffscreenRenderer& operator=(const OffscreenRenderer&) = delete;

  void setCamera(const CameraSettings& camera);
  const CameraSettings& camera() const;

  /// How models are drawn: shaded in their colours, or as an X-ray (fluoroscopy_view.hpp): black,
  /// unlit, at the opacity of their X-ray opacity (models that stop none are skipped).
  enum class Style { kShaded, kXray };
  /// Draws the models' current meshes (models with no triangles are skipped).
  Image render(const std::vector<VisualModel*>& models, Style style = Style::kShaded);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace filum::visual
