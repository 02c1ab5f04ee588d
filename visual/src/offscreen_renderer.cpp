#include "filum/visual/offscreen_renderer.hpp"

#include <atomic>
#include <cstring>
#include <stdexcept>
#include <string>

#include "filum/visual/display_server.hpp"

#if FILUM_WITH_OPENCV
#include <opencv2/core.hpp>
#include <opencv2/viz.hpp>
#endif

namespace filum::visual {

const char* renderingUnavailableMessage() {
  return "pictures, videos and the interactive window need OpenCV, which this build left out: reconfigure with "
         "-DFILUM_WITH_OPENCV=ON (Debian packages libopencv-viz-dev libopencv-imgcodecs-dev libopencv-videoio-dev "
         "libopencv-imgproc-dev, see scripts/setup.sh)";
}

#if FILUM_WITH_OPENCV

bool renderingAvailable() { return true; }

namespace {

cv::viz::Color vizColor(const Vec3& rgb) {
  return cv::viz::Color(255.0 * rgb.z(), 255.0 * rgb.y(), 255.0 * rgb.x());  // viz colours are BGR
}

}  // namespace

struct OffscreenRenderer::Impl {
  std::shared_ptr<DisplayServer> display;
  cv::viz::Viz3d window;
  CameraSettings camera;
  int shown = 0;  // widgets "model_0" .. "model_{shown−1}" currently in the window

  // Each renderer its own window: viz shares the windows of one name, and a run renders two views
  // (the camera's and the fluoroscope's) that must not share a camera.
  Impl() : display(DisplayServer::ensure()), window(uniqueName()) { window.setOffScreenRendering(); }

  static std::string uniqueName() {
    static std::atomic<int> count{0};
    const int k = count++;
    return k == 0 ? std::string("filum") : "filum " + std::to_string(k + 1);
  }

  void apply(const CameraSettings& c) {
    camera = c;
    window.setWindowSize(cv::Size(c.width, c.height));
    window.setBackgroundColor(vizColor(c.background));
    // The pose first (viz resets the clipping range there), then the intrinsics of the pinhole
    // model of camera.hpp: focal length f in pixels, principal point at the image centre.
    // viz's camera y axis points down in the image, so its "y direction" is −up.
    window.setViewerPose(cv::viz::makeCameraPose(cv::Vec3d(c.position.data()), cv::Vec3d(c.look_at.data()),
                                                 cv::Vec3d(-c.up.x(), -c.up.y(), -c.up.z())));
    const double f = c.focalPixels();
    cv::viz::Camera intrinsics(f, f, 0.5 * c.width, 0.5 * c.height, cv::Size(c.width, c.height));
    const double distance = (c.look_at - c.position).norm();
    intrinsics.setClip(cv::Vec2d(1e-3 * distance, 1e3 * distance));
    window.setCamera(intrinsics);
    window.removeAllLights();
    if (c.lights.empty()) {
      // A headlight at the camera and a dimmer fill light from above.
      window.addLight(cv::Vec3d(c.position.data()), cv::Vec3d(c.look_at.data()), cv::viz::Color::white(),
                      cv::viz::Color::white(), cv::viz::Color(40, 40, 40), cv::viz::Color::white());
      const Vec3 above = c.look_at + distance * Vec3(0.3, -0.2, 1.0).normalized();
      window.addLight(cv::Vec3d(above.data()), cv::Vec3d(c.look_at.data()), cv::viz::Color(110, 110, 110),
                      cv::viz::Color(110, 110, 110), cv::viz::Color::black(), cv::viz::Color::black());
    } else {
      for (const Light& light : c.lights)
        window.addLight(cv::Vec3d(light.position.data()), cv::Vec3d(c.look_at.data()), vizColor(light.color),
                        vizColor(light.color), cv::viz::Color(30, 30, 30), cv::viz::Color::white());
    }
  }
};

OffscreenRenderer::OffscreenRenderer(const CameraSettings& camera) : impl_(std::make_unique<Impl>()) {
  impl_->apply(camera);
}

OffscreenRenderer::~OffscreenRenderer() = default;

void OffscreenRenderer::setCamera(const CameraSettings& camera) { impl_->apply(camera); }

const CameraSettings& OffscreenRenderer::camera() const { return impl_->camera; }

Image OffscreenRenderer::render(const std::vector<VisualModel*>& models, Style style) {
  const bool xray = style == Style::kXray;
  int count = 0;
  for (const VisualModel* model : models) {
    if (xray && !(model->xrayOpacity() > 0.0)) continue;
    for (int i = 0; i < model->meshCount(); ++i) {
      const TriangleMesh& mesh = model->mesh(i);
      if (mesh.triangleCount() == 0) continue;
      // The vertices and normals (V × 3 row-major doubles) are viewed as 1 × V three-channel
      // rows; polygons are "3 a b c" per triangle.
      const cv::Mat cloud(1, mesh.vertexCount(), CV_64FC3, const_cast<double*>(mesh.vertices.data()));
      const cv::Mat normals(1, mesh.vertexCount(), CV_64FC3, const_cast<double*>(mesh.normals.data()));
      cv::Mat polygons(1, 4 * mesh.triangleCount(), CV_32SC1);
      int* p = polygons.ptr<int>();
      for (int f = 0; f < mesh.triangleCount(); ++f) {
        *p++ = 3;
        for (int k = 0; k < 3; ++k) *p++ = mesh.triangles(f, k);
      }
      const std::string id = "model_" + std::to_string(count++);
      cv::viz::WMesh widget(cloud, polygons, cv::noArray(), normals);
      widget.setColor(xray ? cv::viz::Color::black() : vizColor(model->material().color));
      impl_->window.showWidget(id, widget);
      impl_->window.setRenderingProperty(id, cv::viz::SHADING, cv::viz::SHADING_PHONG);
      // An X-ray layer transmits 1 − a of what lies behind it, whatever the light: unlit black.
      impl_->window.setRenderingProperty(id, cv::viz::LIGHTING, xray ? 0.0 : 1.0);
      impl_->window.setRenderingProperty(id, cv::viz::OPACITY, xray ? model->xrayOpacity() : model->material().opacity);
    }
  }
  for (int k = count; k < impl_->shown; ++k) impl_->window.removeWidget("model_" + std::to_string(k));
  impl_->shown = count;
  const cv::Mat shot = impl_->window.getScreenshot();  // renders, BGR 8-bit
  if (shot.empty() || shot.type() != CV_8UC3) throw std::runtime_error("viz returned no picture");
  Image image(shot.cols, shot.rows);
  for (int y = 0; y < shot.rows; ++y)
    std::memcpy(image.bgr.data() + 3 * static_cast<std::size_t>(y) * shot.cols, shot.ptr(y), 3 * shot.cols);
  return image;
}

#else

bool renderingAvailable() { return false; }

struct OffscreenRenderer::Impl {
  CameraSettings camera;
};

OffscreenRenderer::OffscreenRenderer(const CameraSettings&) { throw std::runtime_error(renderingUnavailableMessage()); }
OffscreenRenderer::~OffscreenRenderer() = default;
void OffscreenRenderer::setCamera(const CameraSettings&) {}
const CameraSettings& OffscreenRenderer::camera() const { return impl_->camera; }
Image OffscreenRenderer::render(const std::vector<VisualModel*>&, Style) { throw std::runtime_error(renderingUnavailableMessage()); }

#endif

}  // namespace filum::visual
