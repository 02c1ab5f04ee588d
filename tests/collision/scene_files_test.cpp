// The collision scenes of apps/scenes: threads.json (paper Fig. 1c in silicone vessel loops) — eleven threads fall into
// contact and never pass through each other; organ.json — a vessel loop drapes over the triangle-mesh
// organ and never sinks into it.
#include <cmath>
#include <iostream>

#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "crossing_watch.hpp"
#include "filum/collision/triangle_mesh_obstacle.hpp"

namespace filum::collision {
namespace {

const std::string kScenes = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/";

TEST(SceneFiles, ElevenThreadsFallIntoContactAndNeverCross) {
  auto scene = loadScene(kScenes + "threads.json", app::makeFactory());
  ASSERT_EQ(scene->bodies().size(), 11u);
  EXPECT_EQ(scene->constraintViolation(scene->state()).size(), 33);  // 3 rows per thread
  const auto& pipeline = test::pipelineOf(*scene);
  const double r = pipeline.models().front()->radius();
  // 0.3 s: the threads swing down through each other; 40 samples per 8 cm thread, neighbours
  // along a thread within 4 samples (8 mm).
  test::CrossingWatch w;
  Points before = test::CrossingWatch::sample(*scene, scene->state(), 40);
  int most_contacts = 0;
  for (int k = 0; k < 3000; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << report.message;
    most_contacts = std::max(most_contacts, pipeline.statistics().thread_contacts);
    const Points after = test::CrossingWatch::sample(*scene, scene->state(), 40);
    w.check(before, after, 4, r, 40);
    before = after;
  }
  std::cout << "  threads.json: up to " << most_contacts << " thread contacts, closest centre lines "
            << w.min_distance * 1e3 << " mm (contact at " << 2e3 * r << " mm), " << w.close_pairs
            << " close pair-steps, " << w.sign_flips << " sign flips, " << w.crossings << " crossings\n";
  EXPECT_GT(most_contacts, 10);
  EXPECT_EQ(w.crossings, 0);
  EXPECT_EQ(w.sign_flips, 0);
  // Threads in contact are 2r apart; the scene (Scene::advance) redoes in halves, down to dt/8,
  // every step that brought two chords' centre lines closer than r and closer than at its start
  // (ContactPipeline max_penetration, ½ of 2r by default: a contact the step's detection missed),
  // and the contacts' Baumgarte term pushes a pair out (g₁ ≥ 0.75 g₀ for a penetration g₀ < 0 at
  // ω = 0.5/h): no pair goes below r unless even dt/8 missed it.
  EXPECT_GT(w.min_distance, r);
  std::cout << "  steps redone in halves for a missed contact: " << scene->contactHalvings() << '\n';
}

#ifdef FILUM_WITH_CGAL
TEST(SceneFiles, AThreadDrapesOverTheOrganAndNeverSinksIntoIt) {
  auto scene = loadScene(kScenes + "organ.json", app::makeFactory());
  const auto& pipeline = test::pipelineOf(*scene);
  const TriangleMeshObstacle* organ = nullptr;
  for (const Obstacle* o : pipeline.obstacles())
    if (auto* mesh = dynamic_cast<const TriangleMeshObstacle*>(o)) organ = mesh;
  ASSERT_NE(organ, nullptr);
  const double r = pipeline.models().front()->radius();
  // 1 s: the thread falls 1.5 cm, lands on the organ and slides down its flanks.
  double deepest = 0.0;  // largest depth of a curve point inside the organ (m)
  const long steps = std::lround(1.0 / scene->settings().dt), every = std::max(1L, steps / 100);
  for (long k = 1; k <= steps; ++k) {
    ASSERT_TRUE(scene->step().ok);
    if (k % every) continue;
    const Points curve = test::CrossingWatch::sample(*scene, scene->state(), 200);
    for (int i = 0; i < curve.rows(); ++i) {
      const Vec3 x = curve.row(i).transpose();
      if (organ->surface().inside(x)) deepest = std::max(deepest, (x - organ->surface().closestPoint(x)).norm());
    }
  }
  int on_organ = 0;
  for (const Contact& c : pipeline.contacts()) on_organ += c.obstacle == 0;
  std::cout << "  organ.json: " << on_organ << " contacts with the organ after 1 s, centre line at most "
            << deepest * 1e3 << " mm inside its surface (thread radius " << r * 1e3 << " mm)\n";
  EXPECT_GT(on_organ, 10);
  // The centre line stays outside the organ: a point inside would mean the thread sank by more
  // than its radius.
  EXPECT_EQ(deepest, 0.0);
}
#endif

}  // namespace
}  // namespace filum::collision
