// apps/scenes/intestine.json played as `filum run` plays it: the bowel never enters itself by more
// than a tenth of its radius and stays in the abdominal cavity, the grasper lifts a loop and lets
// it go back onto the others, the mesentery pulls a lifted loop back, and the metrics count the
// length that passed between the graspers.
#include <gtest/gtest.h>

#include <cmath>

#include "filum/collision/triangle_mesh_obstacle.hpp"
#include "filum/geometry/arc_length.hpp"
#include "filum/mechanics/tissue_attachment.hpp"
#include "support/instrument_scene_run.hpp"

namespace filum {
namespace {

struct Intestine : test::InstrumentSceneRun {
  const collision::TriangleMeshObstacle* cavity = nullptr;
  const mechanics::TissueAttachment* mesentery = nullptr;
  static constexpr int kSamples = 150;

  Intestine() : InstrumentSceneRun("intestine.json") {
    for (const auto* mesh : components<collision::TriangleMeshObstacle>())
      if (mesh->cavity()) cavity = mesh;
    mesentery = forceField<mechanics::TissueAttachment>();
  }
  const CurveBody& bowel() const { return body(); }
  std::vector<Vec3> axis() const {
    std::vector<Vec3> x(kSamples + 1);
    for (int k = 0; k <= kSamples; ++k) x[k] = bowel().position(scene->state().q, static_cast<double>(k) / kSamples);
    return x;
  }
  /// The deepest overlap of the bowel with itself (m, > 0 when it enters itself): 2r minus the
  /// distance between axis points more than half a turn of its own radius (π r) apart along it.
  double selfOverlap() const {
    const std::vector<Vec3> x = axis();
    std::vector<double> along(x.size(), 0.0);
    for (std::size_t k = 1; k < x.size(); ++k) along[k] = along[k - 1] + (x[k] - x[k - 1]).norm();
    const double r = bowel().radius();
    double overlap = -std::numeric_limits<double>::infinity();
    for (std::size_t i = 0; i < x.size(); ++i)
      for (std::size_t j = i + 1; j < x.size(); ++j)
        if (along[j] - along[i] > M_PI * r) overlap = std::max(overlap, 2.0 * r - (x[j] - x[i]).norm());
    return overlap;
  }
  /// The smallest gap between the bowel's surface and the cavity's wall (m; < 0: through it).
  double wallGap() const {
    double gap = std::numeric_limits<double>::infinity();
    collision::SurfaceSample sample;
    for (const Vec3& x : axis())
      if (cavity->sample(x, 1.0, sample)) gap = std::min(gap, sample.distance - bowel().radius());
    return gap;
  }
};

TEST(Intestine, TheBowelIsLiftedLetGoAndRunWithoutEnteringItselfOrLeavingTheCavity) {
  Intestine run;
  ASSERT_NE(run.cavity, nullptr);
  ASSERT_NE(run.mesentery, nullptr);
  const int right = run.instrumentIndex("right"), left = run.instrumentIndex("left");
  ASSERT_GE(right, 0);
  ASSERT_GE(left, 0);
  const double r = run.bowel().radius();
  // The loop the right grasper lifts first, where it lay at the start.
  const double lifted_at = 0.32;
  const double start_height = run.bowel().position(run.scene->state().q, lifted_at).z();
  // The bowel's length from s = 0 as it lies at the start, at 1001 abscissas (as the metric reads it).
  const geometry::ArcLengthParameterization arc(run.bowel().basis(), run.bowel().block(run.scene->state().q));
  std::vector<double> length_at(1001);
  for (int k = 0; k <= 1000; ++k) length_at[k] = arc.lengthAt(k / 1000.0);
  const auto lengthAt = [&](double s) {
    const double at = 1000.0 * s, fraction = at - std::floor(at);
    const int below = std::min(999, static_cast<int>(at));
    return (1.0 - fraction) * length_at[below] + fraction * length_at[below + 1];
  };
  double overlap = -1.0, gap = 1.0, highest = start_height, pull_at_highest = 0.0;
  std::vector<double> grasped;  // abscissas of the grasps, in order
  std::vector<char> was_holding(run.instruments->size(), 0);
  for (long k = 0; k < run.steps(); ++k) {
    ASSERT_TRUE(run.step()) << "step " << k;
    for (int i = 0; i < run.instruments->size(); ++i) {
      const haptics::Instrument& grasper = run.instruments->instrument(i);
      if (grasper.holding() && !was_holding[i]) grasped.push_back(grasper.hold()->grasp.abscissa());
      was_holding[i] = grasper.holding();
    }
    if (grasped.size() == 1 && run.instruments->instrument(right).holding()) {
      const double height = run.bowel().position(run.scene->state().q, grasped.front()).z();
      if (height > highest) {
        highest = height;
        pull_at_highest = 0.0;
        for (int i = 0; i < run.mesentery->count(); ++i)
          pull_at_highest += run.mesentery->springForce(run.scene->state(), i).z();
      }
    }
    if (k % 10 == 0) {
      overlap = std::max(overlap, run.selfOverlap());
      gap = std::min(gap, run.wallGap());
    }
  }
  // Never into itself by more than a tenth of its radius: the requirement, not a bound of the
  // method. Loops touch through the chords between their contact spheres (one radius apart), which
  // lie inside the skin by at most the sagitta 2r − √3.5 r ≈ 0.13 r at a chord's middle; what is
  // measured on this scene is 2 % of r.
  EXPECT_LT(overlap, 0.1 * r);
  // In the cavity: the skin between two spheres may dip into the wall by the sagitta
  // r − √(r² − (h/2)²) = 2.0 mm (h = r = 15 mm); the rows' compliance adds micrometres.
  EXPECT_GT(gap, -(r - std::sqrt(r * r - 0.25 * r * r)) - 1e-5);

  // Three grasps: the loop at s ≈ 0.32, then the run of the bowel at s ≈ 0.59 and 0.67.
  ASSERT_EQ(grasped.size(), 3u);
  EXPECT_NEAR(grasped[0], lifted_at, 0.02);
  // Lifted: the jaws rise 5 cm and hold their point within the bowel's radius, so the point rises
  // by at least 5 cm − r; the mesentery, taut, pulls the bowel back down.
  EXPECT_GT(highest - start_height, 0.05 - r);
  EXPECT_LT(pull_at_highest, 0.0);
  // Let go: it falls back onto the loops, at most one diameter above where it lay.
  EXPECT_LT(run.bowel().position(run.scene->state().q, grasped[0]).z() - start_height, 2.0 * r);

  // Inspected: the span between the second and the third grasp (8 cm apart, a step shorter than
  // max_step = 10 cm), none between the first and the second (a jump of 25 cm), as a fraction of
  // the bowel's length — both measured as it lay at the start, from the same table (round-off).
  ASSERT_GT(lengthAt(grasped[1]) - lengthAt(grasped[0]), 0.1);
  const double step = std::abs(lengthAt(grasped[2]) - lengthAt(grasped[1]));
  ASSERT_LT(step, 0.1);
  const auto summary = run.instruments->metrics().summary();
  ASSERT_TRUE(summary.contains("inspected_length"));
  EXPECT_NEAR(summary["inspected_length"].get<double>(), step, 1e-12);
  EXPECT_NEAR(summary["inspected_fraction"].get<double>(), step / length_at.back(), 1e-12);
}

}  // namespace
}  // namespace filum
