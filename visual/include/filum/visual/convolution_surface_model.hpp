// ConvolutionSurfaceModel (scene type "ConvolutionSurfaceModel"): a spline drawn as a
// convolution surface ([Lenoir talk 2008] draws intestines this way: neighbouring loops blend smoothly
// where they touch) — the skeleton is the curve as a polyline of chords at equal arc length
// (geometry::ConvolutionSurface::addCurve), the surface is meshed by CGAL
// (convolution_surface_mesher.hpp). Meshing costs far more than skinning, so the mesh may be
// refreshed only every k-th update ("every").
//
// Scene parameters: "radius" (m, default the body's; where its section changes along it, as a
// rod's spans, each chord takes the body's radius at its middle abscissa by its weight in the
// field, and the defaults below take the thinnest section's radius), "sharpness" (1/m, default
// 1/radius), "segments" (skeleton chords, default 4 per polynomial piece; a chord across a step
// of the section takes one side's radius, so the step is placed to within a chord), "facet_size"
// (m, default radius / 2), "approximation" (m, default radius / 20), "angle" (degrees, default 30),
// "every" (default 1), "color", "opacity". Needs CGAL (CMake option FILUM_WITH_CGAL).
#pragma once

#include <memory>
#include <optional>

#include "filum/visual/convolution_surface_mesher.hpp"
#include "filum/visual/visual_model.hpp"

namespace filum::visual {

class ConvolutionSurfaceModel final : public VisualModel {
 public:
  struct Options {
    std::optional<double> radius;      // m
    double sharpness = 0.0;            // 1/m, 0: 1/radius
    std::optional<int> segments;
    std::optional<double> facet_size;  // m
    std::optional<double> approximation;
    double angle_degrees = 30.0;
    int every = 1;
  };
  explicit ConvolutionSurfaceModel(Options options) : options_(options) {}
  static std::unique_ptr<ConvolutionSurfaceModel> fromParams(const Params& p);

  std::string typeName() const override { return "ConvolutionSurfaceModel"; }
  /// X-ray: a body's skin, as GeneralizedCylinderModel.
  double defaultXrayOpacity() const override { return 0.85; }
  bool drawsBody() const override { return true; }
  void update(const SceneState& s) override;
  /// One surface per strand of the body (one for an uncut curve: CurveBasis::strands).
  int meshCount() const override { return static_cast<int>(meshes_.size()); }
  const TriangleMesh& mesh(int strand = 0) const override { return meshes_.at(strand); }

 protected:
  void init(const Scene& scene) override;

 private:
  Options options_;
  double radius_ = 0.0;
  bool varies_ = false;  // each chord weighted to the body's radius at it
  int segments_ = 0;
  SurfaceMeshingCriteria criteria_;
  long updates_ = 0;
  std::vector<TriangleMesh> meshes_;
};

}  // namespace filum::visual
