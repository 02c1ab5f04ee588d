// NavigationMetrics: what an interventional trainer scores of a catheter, guidewire or coil run
// (the scene's "navigation" block), per instrument, from its curve body at every step:
//   inserted length  (x_hub(t) − x_hub(0))·a₀, a₀ the hub's initial tangent (m): how far the hand
//                    pushed the instrument through the introducer (negative: pulled back);
//   roll             the roll the hub's RodEndFrame holds (rad): how far the hand turned it;
//   tip              the distal end P(1), the branch of the vessel tree it lies in, its distance
//                    to the target point (m, when the scene gives one), the time the tip first
//                    lay in the target branch (s, when it names one);
//   wall force       Σ |F_c| over the instrument's contacts with the lumen (N), its maximum over
//                    the run and the time it spent above the force limit (s): a wire pushed
//                    hard against the wall risks a dissection;
//   tip path length  Σ |x_tip(t_k+1) − x_tip(t_k)| (m);
//   fluoroscopy time how long the X-ray pedal was pressed (s; fluoroscopy_pedal.hpp), when the
//                    scene has a "fluoroscopy" block: the dose a trainer scores;
//   packing density  Σ ∫ π r² dℓ / V of the coils in the aneurysm (coil_packing.hpp), when the scene
//                    names one: its value at every step and its largest.
// Scene:
//   "navigation": {"instruments": ["guidewire"] (or "instrument": "guidewire": node paths of
//                  curve bodies, the hub at s = 0 and the tip at s = 1),
//                  "vessels": node path of the node holding the VesselLumenObstacle,
//                  "target": [x, y, z] (m, optional), "target_branch": name (optional),
//                  "force_limit": N (default 0.5),
//                  "aneurysm": {"branches": [names of the vessel tree's branches: the sac, its
//                               neck], "coils": [node paths of curve bodies],
//                               "spacing": m (the volume grid's; default: coil_packing.hpp)},
//                  "device": a haptic device at an instrument's hub (hub_device.hpp)}
//   "instruments" may be left out when an "aneurysm" is scored.
// Outputs (filum run): metrics.csv (one row per step) and metrics.json (the summary).
#pragma once

#include <fstream>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"
#include "filum/haptics/coil_packing.hpp"
#include "filum/haptics/fluoroscopy_pedal.hpp"

namespace filum::collision {
class VesselLumenObstacle;
}
namespace filum::mechanics {
class RodEndFrame;
}

namespace filum::haptics {

class NavigationMetrics {
 public:
  struct Instrument {
    std::string name;
    const CurveBody* body = nullptr;
    const mechanics::RodEndFrame* hub_frame = nullptr;  // nullptr: no roll reported
    Vec3 hub_start = Vec3::Zero(), axis = Vec3::UnitZ();
    // This step's values.
    double inserted = 0.0, roll = 0.0;
    Vec3 tip = Vec3::Zero();
    int branch = -1;
    double wall_force = 0.0, max_contact_force = 0.0;
    // Over the run.
    double max_inserted = 0.0, max_wall_force = 0.0, time_above_limit = 0.0, tip_path = 0.0;
    double target_distance = -1.0, min_target_distance = -1.0;  // m; −1 without a target point
    double reached_time = -1.0;  // s; −1 until the tip lies in the target branch
  };

  /// The metrics the scene's "navigation" block asks for, or nullptr when it has none. Throws
  /// SceneError naming the place in the file (unknown node, no lumen, unknown branch).
  static std::unique_ptr<NavigationMetrics> fromScene(const nlohmann::json& document, const std::string& source,
                                                     const Scene& scene);

  /// The instruments at the start (hub position and direction); call once before the first step.
  void start(const Scene& scene);
  /// One step done: every instrument's values, the CSV row.
  void afterStep(const Scene& scene, double h);
  /// metrics.csv from now on.
  void openCsv(const std::string& path);
  /// metrics.json: the summary.
  void writeSummary(const std::string& path) const;
  nlohmann::json summary() const;
  /// A few lines for the run's log.
  std::string text() const;

  int instrumentCount() const { return static_cast<int>(instruments_.size()); }
  const Instrument& instrument(int i) const { return instruments_[i]; }
  const collision::VesselLumenObstacle& lumen() const { return *lumen_; }
  int targetBranch() const { return target_branch_; }
  /// The aneurysm scored, nullptr without an "aneurysm" block.
  const CoilPacking* packing() const { return packing_.get(); }
  /// This step's packing density and its largest over the run (0 without an aneurysm).
  double packingDensity() const { return packing_density_; }
  double maxPackingDensity() const { return max_packing_density_; }

 private:
  NavigationMetrics() = default;
  /// The instrument's values at the scene's current state.
  void measure(const Scene& scene, Instrument& m) const;
  void writeRow(double t);
  /// The coils' lengths in the aneurysm and the packing density at the scene's state.
  void measurePacking(const Scene& scene);
  /// Reads the "aneurysm" block of p.
  void readAneurysm(const Scene& scene, const Params& p);

  struct Coil {
    std::string name;
    const CurveBody* body = nullptr;
    double length_inside = 0.0;  // m, this step
  };

  std::vector<Instrument> instruments_;
  const collision::VesselLumenObstacle* lumen_ = nullptr;
  int lumen_index_ = -1;  // among the contact pipeline's obstacles
  std::unique_ptr<FluoroscopyPedal> pedal_;  // nullptr: no "fluoroscopy" block
  std::optional<Vec3> target_;
  int target_branch_ = -1;
  double force_limit_ = 0.5;
  std::unique_ptr<CoilPacking> packing_;  // nullptr: no "aneurysm" block
  std::vector<Coil> coils_;
  double packing_density_ = 0.0, max_packing_density_ = 0.0;
  double time_ = 0.0;
  std::ofstream csv_;
  bool csv_failed_ = false;
};

}  // namespace filum::haptics
