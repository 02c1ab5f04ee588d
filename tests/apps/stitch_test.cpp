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
  int skin_holes_checked = 0;
  double worst_face = 0.0, largest_tip_step = 0.0, worst_depth = 0.0, bite_error = 0.0, deepest = 0.0;
  Vec3 last_tip = Vec3::Zero(), down_crossing = Vec3::Zero(), up_crossing = Vec3::Zero();
  // The skin's plane z = z_s over the lips (their edges r_e below it; they sag a few µm under their
  // weight before the needle arrives, evenly along them, and then stay put until the thread holds)
  // and the cut faces at y = ±y_cut: measured from the lips' edges at their middles.
  const auto skin = [&](const SceneState& st) { return wound.lip(0).position(st.q, 0.5).z() + set.edge_radius; };
  const auto cut = [&](const SceneState& st, int k) { return wound.lip(k).position(st.q, 0.5).y() + (k == 0 ? 1 : -1) * set.edge_radius; };
  for (long k = 0; k < steps; ++k) {
    run.instruments->beforeStep(*run.scene);
    const SceneState& st = run.scene->state();
    const haptics::Needle& needle = run.instruments->needle(0);
    const Vec3 tip = needle.tip(needle.pose());
    const double z_s = skin(st);
    if (k > 0) {
      largest_tip_step = std::max(largest_tip_step, (tip - last_tip).norm());
      // Where the tip's step crossed the skin's plane, by linear interpolation in z (the step is a
      // segment: the same segment the wound bisects).
      if ((last_tip.z() - z_s) * (tip.z() - z_s) < 0.0) {
        const Vec3 crossing = last_tip + (z_s - last_tip.z()) / (tip.z() - last_tip.z()) * (tip - last_tip);
        (tip.z() < z_s ? down_crossing : up_crossing) = crossing;
      }
    }
    last_tip = tip;
    // The deepest the tip goes inside a lip (beyond a cut face, below the skin), independently of
    // the wound's slabs.
    if (tip.z() < z_s && (tip.y() <= cut(st, 0) || tip.y() >= cut(st, 1))) deepest = std::max(deepest, z_s - tip.z());
    // A new hole lies on its lip's surface — the skin (v = 0) for the ones on top, the cut face
    // (u = 0) for the ones in the wound — to the bisection's precision: 40 halvings of a step's
    // motion (< 0.1 mm) leave 1e-16 m; the closest point on the edge is found to round-off of its
    // 4 cm (1e-17 m). 1e-12 m is far above both and far below anything a wrong face would give.
    for (; holes_seen < wound.holes().size(); ++holes_seen) {
      const haptics::Wound::Hole& h = wound.holes()[holes_seen];
      const haptics::Wound::LipPoint at = wound.locate(st, h.lip, wound.holePosition(st, h));
      worst_face = std::max(worst_face, std::min(std::abs(at.depth), std::abs(at.across)));
      if (h.face != haptics::Wound::Face::kSkin) continue;
      // A skin hole is where the tip's step crossed the skin's plane (going in for an entry, a few
      // steps ago: the tip pressed 1 mm before the skin gave way; coming out for an exit, this
      // step), its bite that point's distance from the cut face, |y − y_cut|. The same crossing by
      // bisection and by interpolation: to the bisection's 1e-16 m and the lips' stillness between
      // the crossing and the puncture (settled: e^-50 of their sag): 1e-9 m is far above both.
      const Vec3 crossing = h.entry ? down_crossing : up_crossing;
      bite_error = std::max(bite_error, std::abs(std::abs(crossing.y() - cut(st, h.lip)) - h.from_edge));
      ++skin_holes_checked;
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
  EXPECT_EQ(skin_holes_checked, 2);
  EXPECT_LT(bite_error, 1e-9);

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
  // the plane x = 0, ⊥ the edges along x: 90° to round-off), its depth the deepest the tip went
  // inside a lip at the steps' starts, as measured above from the planes of the skin and the cut
  // faces (the same samples: to round-off).
  const std::vector<haptics::Wound::Stitch> stitches = wound.stitches();
  ASSERT_EQ(stitches.size(), 1u);
  EXPECT_EQ(stitches[0].entry, 0);
  EXPECT_EQ(stitches[0].exit, 3);
  EXPECT_EQ(stitches[0].entry_bite, holes[0].from_edge);
  EXPECT_EQ(stitches[0].exit_bite, holes[3].from_edge);
  EXPECT_NEAR(stitches[0].angle, M_PI / 2, 1e-9);
  EXPECT_NEAR(stitches[0].depth, deepest, 1e-12);
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
