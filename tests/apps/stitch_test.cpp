// apps/scenes/stitch.json (haptics/wound.hpp): a curved needle driven through both lips of a wound
// makes four holes where its tip crossed the skin or the cut faces — each on the slab's surface, a
// puncture only once the tip pressed the puncture force — the thread runs through all four and
// stays in them, it never enters the skin elsewhere, and its pull brings the lips together until
// they meet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "filum/all_components.hpp"
#include "filum/collision/contact_pipeline.hpp"
#include "filum/constraints/sliding_point_constraint.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/core/scene_loader.hpp"
#include "filum/haptics/instrument_set.hpp"

namespace filum {
namespace {

struct StitchRun {
  nlohmann::json document;
  std::unique_ptr<Scene> scene;
  std::unique_ptr<haptics::InstrumentSet> instruments;
  explicit StitchRun(nlohmann::json doc) : document(std::move(doc)) {
    const std::string path = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/stitch.json";
    scene = loadScene(document, path, app::makeFactory());
    instruments = haptics::InstrumentSet::fromScene(document, path, *scene);
  }
  static nlohmann::json file() { return readJsonFile(std::string(FILUM_SOURCE_DIR) + "/apps/scenes/stitch.json"); }
  const haptics::Wound& wound() const { return *instruments->wound(); }
  const CurveBody& thread() const { return *scene->bodies().front()->curve(); }
};

TEST(Stitch, FourHolesHoldTheThreadWhichNeverEntersTheSkinElsewhereAndTheLipsMeet) {
  StitchRun run(StitchRun::file());
  const haptics::Wound& wound = run.wound();
  const haptics::Wound::Settings& set = wound.settings();
  const double dt = run.scene->settings().dt;
  const long steps = std::lround(run.scene->settings().duration / dt);
  const double r = run.thread().radius();
  std::size_t holes_seen = 0;
  double worst_face = 0.0, largest_tip_step = 0.0, worst_depth = 0.0, bite_error = 0.0;
  double centre_wander = 0.0, plane_wander = 0.0;
  Vec3 centre0 = Vec3::Zero(), normal0 = Vec3::Zero();
  Vec3 last_tip = Vec3::Zero();
  for (long k = 0; k < steps; ++k) {
    run.instruments->beforeStep(*run.scene);
    const SceneState& st = run.scene->state();
    const haptics::Needle& needle = run.instruments->needle(0);
    const Vec3 tip = needle.tip(needle.pose());
    if (k > 0) largest_tip_step = std::max(largest_tip_step, (tip - last_tip).norm());
    last_tip = tip;
    if (k == 0) {
      centre0 = needle.pose().position;
      normal0 = needle.pose().rotation.col(2);
    }
    // Held by a holder (from its first catch on), the needle is meant to turn about its centre.
    if (needle.holder >= 0) {
      centre_wander = std::max(centre_wander, (needle.pose().position - centre0).norm());
      plane_wander = std::max(plane_wander, (needle.pose().rotation.col(2) - normal0).norm());
    }
    // A new hole lies on its lip's surface — the skin (v = 0) for the ones on top, the cut face
    // (u = 0) for the ones in the wound — to the bisection's precision: 40 halvings of a step's
    // motion (< 0.1 mm) leave 1e-16 m; the closest point on the edge is found to round-off of its
    // 4 cm (1e-17 m). 1e-12 m is far above both and far below anything a wrong face would give.
    for (; holes_seen < wound.holes().size(); ++holes_seen) {
      const haptics::Wound::Hole& h = wound.holes()[holes_seen];
      const haptics::Wound::LipPoint at = wound.locate(st, h.lip, wound.holePosition(st, h));
      worst_face = std::max(worst_face, std::min(std::abs(at.depth), std::abs(at.across)));
      if (h.face != haptics::Wound::Face::kSkin) continue;
      // The bite: where the needle's circle meets the skin's plane z = z_s (the lip's edge r_e
      // below it), P(θ) = c + R (cos θ u + sin θ v) with a cos θ + b sin θ = (z_s − c_z) / R,
      // a = u_z, b = v_z: θ = atan2(b, a) ± acos(·/√(a² + b²)), the root nearer the hole.
      const haptics::RigidPose& pose = needle.pose();
      const double z_s = wound.lip(h.lip).position(st.q, h.lip_abscissa).z() + set.edge_radius;
      const Vec3 u = pose.rotation.col(0), v = pose.rotation.col(1);
      const double a = u.z(), b = v.z(), R = needle.settings().radius;
      const double phase = std::atan2(b, a), spread = std::acos((z_s - pose.position.z()) / (R * std::hypot(a, b)));
      double nearest = std::numeric_limits<double>::infinity(), bite = 0.0;
      for (const double theta : {phase + spread, phase - spread}) {
        const Vec3 p = pose.position + R * (std::cos(theta) * u + std::sin(theta) * v);
        const double d = (p - wound.holePosition(st, h)).norm();
        if (d < nearest) {
          nearest = d;
          bite = wound.locate(st, h.lip, p).across;
        }
      }
      // The hole is where the tip crossed the skin, a few steps ago for an entry (it pressed 1 mm
      // before the skin gave way). Were the needle turned about a fixed centre in a fixed plane, its
      // circle would pass there now too; the script's keyframed turn moves the centre by W_c and
      // tilts the plane by W_n over the run (measured below), so the circle now lies within
      // 2 (W_c + R W_n) of that one, plus the chord of one step of the tip's motion.
      bite_error = std::max(bite_error, std::abs(bite - h.from_edge));
    }
    const StepReport report = run.scene->step();
    ASSERT_TRUE(report.ok) << report.message;
    run.instruments->afterStep(*run.scene);
    // Outside its passage the thread's centre line stays out of the skin: the contacts hold it at r
    // from the surface, less the overlap the contact solve leaves (a regularized, Baumgarte-held
    // contact: a fraction of r), so a point of the centre line inside the skin (depth > r below
    // touching) would be the thread through the skin.
    const haptics::WoundPad& pad = wound.pad();
    for (int i = 0; i <= 1000; ++i) {
      const double s = i / 1000.0;
      if (pad.passesThrough(run.thread(), s)) continue;
      collision::SurfaceSample sample;
      if (pad.sample(run.thread().position(run.scene->state().q, s), r, sample))
        worst_depth = std::max(worst_depth, r - sample.distance);
    }
  }
  EXPECT_LT(worst_depth, r);
  EXPECT_LT(worst_face, 1e-12);
  const double R_needle = run.instruments->needle(0).settings().radius;
  EXPECT_LE(bite_error, 2.0 * (centre_wander + R_needle * plane_wander) + largest_tip_step);

  // In at the left lip's top, out of its cut face, into the right lip's cut face, out of its top.
  const auto& holes = wound.holes();
  ASSERT_EQ(holes.size(), 4u);
  const int lips[4] = {0, 0, 1, 1};
  const bool entries[4] = {true, false, true, false};
  for (int i = 0; i < 4; ++i) {
    EXPECT_EQ(holes[i].lip, lips[i]) << "hole " << i;
    EXPECT_EQ(holes[i].entry, entries[i]) << "hole " << i;
    EXPECT_GE(holes[i].slot, 0) << "hole " << i << " never held the thread";
  }
  // The skin gave way once the tip pressed 1 N; by the step it did, the tip had gone at most one
  // step's motion deeper: F <= F_p + k_i · (largest step of the tip).
  EXPECT_GE(wound.peakForce(), set.puncture_force);
  EXPECT_LE(wound.peakForce(), set.puncture_force + set.indentation_stiffness * largest_tip_step);

  // The thread is still in all four holes, each within the thread's radius of its hole.
  const SceneState& st = run.scene->state();
  EXPECT_EQ(wound.holdingHoles(), 4);
  for (const constraints::SlidingPointConstraint* c : wound.slots()) {
    if (!c->active()) continue;
    EXPECT_LT(c->gap(st).norm(), r) << c->name();
  }
  // The lips met: their edge spheres press on each other (a contact between the two lip models
  // with a compressive multiplier), at the middle of the wound where the stitch is.
  const auto& pipeline = dynamic_cast<const collision::ContactPipeline&>(*run.scene->collisionPipeline());
  const auto is_lip = [&](int m) { return m >= 0 && &pipeline.models()[m]->curve() != &run.thread(); };
  int pressing = 0;
  for (int i = 0; i < pipeline.contactCount(); ++i) {
    const collision::Contact& c = pipeline.contacts()[i];
    if (is_lip(c.model_a) && is_lip(c.model_b) && c.model_a != c.model_b && pipeline.contactForce(i, st).dot(c.normal) > 0.0)
      ++pressing;
  }
  EXPECT_GT(pressing, 0);
  EXPECT_LT(wound.gap(st), 0.0);  // the cut faces touch (the contacts' overlap: below zero)
  // The stitch, as the metrics report it: from the first hole to the last (in by the left lip's
  // skin, out by the right's), its bites those holes', square across the wound (the needle turns in
  // the plane x = 0, ⊥ the edges along x: 90° to round-off). Its depth is the deepest the tip went
  // inside a lip: the needle's circle (R = 8 mm, centre z_c = √(8² − 6²) mm above the skin) is
  // deepest on the wound's axis, in the gap, so inside a lip at the cut faces |y| = 1 mm:
  // √(R² − 1²) − z_c, to the tip's sampling (a step's motion) and the script's stray from a turn
  // about that fixed centre (as much as the bites stray from the 5 mm it aims at).
  const std::vector<haptics::Wound::Stitch> stitches = wound.stitches();
  ASSERT_EQ(stitches.size(), 1u);
  EXPECT_EQ(stitches[0].entry, 0);
  EXPECT_EQ(stitches[0].exit, 3);
  EXPECT_EQ(stitches[0].entry_bite, holes[0].from_edge);
  EXPECT_EQ(stitches[0].exit_bite, holes[3].from_edge);
  EXPECT_NEAR(stitches[0].angle, M_PI / 2, 1e-9);
  const double R = 0.008, z_c = std::sqrt(R * R - 0.006 * 0.006);
  const double stray = std::max(std::abs(holes[0].from_edge - 5e-3), std::abs(holes[3].from_edge - 5e-3));
  EXPECT_NEAR(stitches[0].depth, std::sqrt(R * R - 1e-6) - z_c, largest_tip_step + stray);
}

TEST(Stitch, ATipDrawnBackBeforeThePunctureForceMakesNoHole) {
  // The needle pushed straight down on the left lip (its tip the circle's lowest point, 2 mm above
  // the skin) by 2 mm + d and drawn back: a tip pressed d = 0.5 mm (0.5 N at 1000 N/m) makes no
  // hole; one pressed d = 1.5 mm punctures once it reaches 1 mm (1 N).
  for (const double d : {0.5e-3, 1.5e-3}) {
    nlohmann::json doc = StitchRun::file();
    const double R = 0.008;
    // The needle in the plane x = 0; its tip at angle −90° (the bottom), 6 mm beside the wound's
    // axis, over the left lip: centre (0, −0.006, R + 0.002); swage at −90° − 135°.
    const double tip = -M_PI / 2, swage = tip - 2.356;
    doc["needles"][0]["center"] = {0.0, -0.006, R + 0.002};
    doc["needles"][0]["start"] = {0.0, std::cos(swage), std::sin(swage)};
    // The suture laid from the swage along the needle's axis, −T(0) = (sin β, −cos β) in (y, z) at
    // the swage's angle β (the swage's holds start without a pull), its tail held where it lies.
    const Vec3 at_swage(0.0, -0.006 + R * std::cos(swage), R + 0.002 + R * std::sin(swage));
    const Vec3 tail = at_swage + 0.15 * Vec3(0.0, std::sin(swage), -std::cos(swage));
    for (auto& component : doc["nodes"][0]["components"]) {
      if (component["type"] == "DynamicSpline") {
        component["control_points"]["from"] = {at_swage.x(), at_swage.y(), at_swage.z()};
        component["control_points"]["to"] = {tail.x(), tail.y(), tail.z()};
      }
      if (component["type"] == "FixedPointConstraint")
        component["path"] = {{{"time", 0.0}, {"position", {tail.x(), tail.y(), tail.z()}}}};
    }
    // Holder A holds it near its swage and moves it down and back up (a straight line: the monotone
    // path stays on it); holder B stays away.
    const double grasp = swage + 0.17;
    const double y = -0.006 + R * std::cos(grasp), z = R + 0.002 + R * std::sin(grasp);
    const double roll = grasp - M_PI / 2;
    nlohmann::json path = nlohmann::json::array(
        {{{"time", 0.0}, {"position", {-0.006, y, z}}, {"direction", {1, 0, 0}}, {"roll", roll}, {"jaw", 1}},
         {{"time", 0.1}, {"position", {-0.006, y, z}}, {"jaw", 0}},
         {{"time", 0.5}, {"position", {-0.006, y, z - 0.002 - d}}},
         {{"time", 0.9}, {"position", {-0.006, y, z}}}});
    doc["instruments"][0]["path"] = path;
    doc["instruments"][1]["path"] = {{{"time", 0.0}, {"position", {-0.1, 0.05, 0.1}}, {"direction", {1, 0, 0}}}};
    doc["duration"] = 1.0;
    StitchRun run(doc);
    double largest_tip_step = 0.0, skin_above_deepest = 0.0;
    Vec3 last_tip = Vec3::Zero();
    for (int k = 0; k < 1000; ++k) {
      run.instruments->beforeStep(*run.scene);
      const haptics::Needle& needle = run.instruments->needle(0);
      const Vec3 tip = needle.tip(needle.pose());
      if (k > 0) largest_tip_step = std::max(largest_tip_step, (tip - last_tip).norm());
      last_tip = tip;
      if (k == 500) {  // t = 0.5 s, the deepest: the skin above the tip (the edge curve r_e below it)
        const haptics::Wound& w = run.wound();
        skin_above_deepest = w.lip(0).position(run.scene->state().q, 0.5).z() + w.settings().edge_radius - tip.z();
      }
      ASSERT_TRUE(run.scene->step().ok);
      run.instruments->afterStep(*run.scene);
    }
    const haptics::Wound& wound = run.wound();
    const double k_i = wound.settings().indentation_stiffness;
    if (d < 1e-3) {
      // F = k_i δ, δ the depth past the entry: deepest at 0.5 s, a step's start, where the tip is
      // d below where it started, 2 mm above the skin (which has sagged by its weight a few µm,
      // settled long before the tip arrives: the lip's ζ = 0.5 at ω = 1000 /s). So δ is the skin's
      // height above the tip there, to round-off (1e-16 m; times k_i, 1e-13 N: 1e-9 N is far above).
      EXPECT_GT(skin_above_deepest, 0.9 * d);
      EXPECT_TRUE(wound.holes().empty());
      EXPECT_NEAR(wound.peakForce(), k_i * skin_above_deepest, 1e-9);
    } else {
      // In through the skin, and out again where it went in: both withdrawn (no passage for the
      // thread); the skin gave way within a step's motion of the tip past the puncture force.
      ASSERT_EQ(wound.holes().size(), 2u);
      EXPECT_TRUE(wound.holes()[0].entry);
      EXPECT_FALSE(wound.holes()[1].entry);
      EXPECT_EQ(wound.holes()[0].lip, 0);
      EXPECT_EQ(wound.holes()[0].slot, haptics::Wound::kWithdrawn);
      EXPECT_EQ(wound.holes()[1].slot, haptics::Wound::kWithdrawn);
      EXPECT_TRUE(wound.stitches().empty());
      EXPECT_GE(wound.peakForce(), wound.settings().puncture_force);
      EXPECT_LE(wound.peakForce(), wound.settings().puncture_force + k_i * largest_tip_step);
    }
  }
}

}  // namespace
}  // namespace filum
