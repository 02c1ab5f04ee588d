// Contact points are body points (core/body_point.hpp): both sides of every contact of a real
// contact set — thread against thread on eleven vessel loops swinging into each other
// (apps/scenes/threads.json), chord points between sphere samples — pass the generic mapping
// test, lie on their models' bodies where the narrow phase found them, and carry a contact force
// up with the virtual work of the force on the relative motion: B·v = F·(v_A − v_B)
// (addContactForce).
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
  // The contacts of the current state: the narrow phase run on it (a step's detection, at its
  // start state), so that the points can be compared with what it found there.
  const SceneState& s = scene->state();
  const_cast<ContactPipeline&>(pipeline).beginStep(*scene, s, scene->settings().dt);
  ASSERT_FALSE(pipeline.contacts().empty());
  int chord_points = 0, compared = 0;
  for (const Contact& c : pipeline.contacts()) {
    // Each side on its collision model's body.
    EXPECT_EQ(c.a.body(), &pipeline.models()[c.model_a]->curve());
    if (!c.againstObstacle()) {
      EXPECT_EQ(c.b.body(), &pipeline.models()[c.model_b]->curve());
      // Where the narrow phase found them: n = (x_A − x_B)/|x_A − x_B| from the closest points of
      // the two chords (narrow_phase.cpp), so x_A − x_B is along n. The points there are
      // p0 + u (p1 − p0) of the sphere centres and Σ w_j q_j of the body points, the same
      // numbers summed in another order: round-off ~1e-16 of O(0.1 m), 1e-13 m asserted.
      // (Chords whose centre lines already touch take the common perpendicular instead.)
      const Vec3 d = c.a.map(s.q) - c.b.map(s.q);
      if (d.norm() > 1e-9) {
        EXPECT_LE((d - c.normal.dot(d) * c.normal).norm(), 1e-13);
        ++compared;
      }
    }
    for (const BodyPoint* point : {&c.a, &c.b}) {
      if (point == &c.b && c.againstObstacle()) continue;
      ASSERT_TRUE(point->attached());
      chord_points += point->onChord();
      // Linear mapping: round-off only (ε |x| / h ≈ 2e-16 · 0.1 m / 1e-6 m = 2e-11), 1e-10.
      test::expectMappingConsistent(*point, point->body()->block(s.q), 1e-6, 1e-10);
    }
    const ContactKinematics k = contactKinematics(c, s);
    // Virtual work: B·v = F·(v_A − v_B) to round-off of the sums (≤ 24 products of O(1) numbers).
    VecX B = VecX::Zero(s.v.size());
    const Vec3 F(0.2, -0.7, 0.5);
    addContactForce(c, F, B);
    const double work = F.dot(k.v_a - (c.againstObstacle() ? Vec3::Zero() : k.v_b));
    EXPECT_NEAR(B.dot(s.v), work, 1e-14 * (1.0 + std::abs(work)));
  }
  EXPECT_GT(chord_points, 0) << "thread–thread contacts lie between sphere samples";
  // The chord points of the sampling (SphereSamplingMapping::chordPoint) are (1 − t) x_k + t x_{k+1}
  // of its centres, placed by the detection above from this state (round-off, 1e-15 m).
  const SphereCollisionModel& model = *pipeline.models().front();
  for (int k = 0; k + 1 < model.sphereCount(); ++k) {
    const BodyPoint point = model.mapping().chordPoint(model.curve(), k, 0.3);
    const Vec3 expected = model.mapping().joinsNext(k)
                              ? Vec3(0.7 * model.centers().row(k).transpose() + 0.3 * model.centers().row(k + 1).transpose())
                              : Vec3(model.centers().row(k).transpose());
    EXPECT_LE((point.map(s.q) - expected).norm(), 1e-15) << "chord " << k;
  }
  EXPECT_GT(compared, 0) << "no thread–thread contact apart enough to compare its direction";
}

}  // namespace
}  // namespace filum::collision
