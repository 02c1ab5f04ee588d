// Contact points are body points (core/body_point.hpp): both sides of every contact of a real
// contact set — thread against thread on eleven vessel loops swinging into each other
// (apps/scenes/threads.json), chord points between sphere samples — pass the generic mapping
// test, sit where the narrow phase found them, and carry a contact force up with the virtual work
// of the force on the relative motion: B·v = F·(v_A − v_B) (addContactForce).
#include <gtest/gtest.h>

#include "collision_scenes.hpp"
#include "support/finite_difference.hpp"

namespace filum::collision {
namespace {

TEST(ContactPoints, AreBodyPointsThatPassTheMappingTestAndCarryForcesWithTheirWork) {
  const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/threads.json";
  auto scene = loadScene(readJsonFile(path), path, app::makeFactory());
  const auto& pipeline = test::pipelineOf(*scene);
  int steps = 0;
  while (pipeline.contacts().size() < 10 && steps < 400) {
    ASSERT_TRUE(scene->step().ok);
    ++steps;
  }
  ASSERT_GE(pipeline.contacts().size(), 10u) << "the loops were expected to touch within 400 steps";
  const SceneState& s = scene->state();
  int chord_points = 0;
  for (const Contact& c : pipeline.contacts()) {
    for (const BodyPoint* point : {&c.a, &c.b}) {
      if (point == &c.b && c.againstObstacle()) continue;
      ASSERT_TRUE(point->attached());
      chord_points += point->onChord();
      // Linear mapping: round-off only (ε |x| / h ≈ 2e-16 · 0.1 m / 1e-6 m = 2e-11), 1e-10.
      test::expectMappingConsistent(*point, point->body()->block(s.q), 1e-6, 1e-10);
    }
    // The contact's points are the narrow phase's: at the found gap (n·(x_A − x_B) − R, evaluated
    // again from the points; a sum of ≤ 12 products of O(0.1 m) numbers, 1e-15 m).
    const ContactKinematics k = contactKinematics(c, s);
    EXPECT_NEAR(k.gap, c.normal.dot(c.a.map(s.q) - (c.againstObstacle() ? k.x_b : c.b.map(s.q))) - c.radius, 1e-15);
    // Virtual work: B·v = F·(v_A − v_B) to round-off of the sums (≤ 24 products of O(1) numbers).
    VecX B = VecX::Zero(s.v.size());
    const Vec3 F(0.2, -0.7, 0.5);
    addContactForce(c, F, B);
    const double work = F.dot(k.v_a - (c.againstObstacle() ? Vec3::Zero() : k.v_b));
    EXPECT_NEAR(B.dot(s.v), work, 1e-14 * (1.0 + std::abs(work)));
  }
  EXPECT_GT(chord_points, 0) << "thread–thread contacts lie between sphere samples";
}

}  // namespace
}  // namespace filum::collision
