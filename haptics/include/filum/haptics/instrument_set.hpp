// InstrumentSet: a scene's "instruments" at run time — the instruments (instrument.hpp), what
// their jaws do between the steps, and the trainee metrics (trainee_metrics.hpp).
//
//   "instruments": [ {"name": ..., "type": "Grasper", "path": [...], ...}, ... ],
//   "needles": [ {"name": ..., "radius": ..., "thread": ..., ...}, ... ]   (needle.hpp; optional)
//   "wound": {"lips": [...], "thread": ..., ...}   (wound.hpp; optional: the lips the needles puncture)
//   "metrics": {"idle_speed": 0.005,     (m/s; optional)
//               "specimen": {"body": "tube", "kept_end": 0},  (optional: the length cut off the
//                 body's end kept in the patient, s = kept_end, is the specimen removed)
//               "inspection": {"body": "bowel", "max_step": 0.1}}  (optional: the length of the
//                 body that passed between the graspers, grasp_coverage.hpp; max_step in m)
//
// Building it adds to the scene, for each instrument, its parts as obstacles of the collision
// pipeline (InstrumentCapsule; with "collide", the default) and on every curve body a coupling
// force field (haptics/tool.hpp) that holds the jaws' point while they hold one; the scene is
// bound again. Per step (the run loop, as for a HapticSession):
//   beforeStep: each instrument to the step's start (its driver), then its jaws: opened, they let
//     go; closed to close_below, they act on the thread between them (grasp, clamp, cut: a cut
//     is a Scene::cut between the steps);
//   afterStep: slips through a grasper's jaws, coagulation under bipolar forceps, the metrics,
//     one row of metrics.csv.
// Instruments are processed in their order in the list: two closing on one step act in that order.
#pragma once

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/core/scene.hpp"
#include "filum/haptics/grasp_coverage.hpp"
#include "filum/haptics/haptic_session.hpp"
#include "filum/haptics/instrument.hpp"
#include "filum/haptics/needle.hpp"
#include "filum/haptics/trainee_metrics.hpp"
#include "filum/haptics/wound.hpp"

namespace filum::haptics {

class InstrumentSet {
 public:
  /// Reads document["instruments"] (null when the scene has none) of the scene file `source`,
  /// adds the instruments' parts and force fields to `scene` and binds it again. Throws
  /// SceneError at the faulty JSON path.
  /// `duration`: the run's length (s), for the servo logs of device-driven instruments.
  static std::unique_ptr<InstrumentSet> fromScene(const nlohmann::json& document, const std::string& source,
                                                  Scene& scene, double duration = 0.0);
  ~InstrumentSet();

  /// Starts the servo loops of device-driven instruments (thread mode) and the Ctrl-C handler.
  void start();
  /// Stops them: forces off. Idempotent.
  void finish();
  /// Whether some device runs on its own thread on the wall clock (the run paces itself).
  bool threaded() const;
  /// Whether Ctrl-C arrived or a servo loop stopped (the run should stop after its step).
  bool interrupted() const;
  /// The hand takes instrument i over from its script (the mouse of `filum view`): from now on
  /// steer() moves its hinge and its jaws, its orientation kept as it was. A device-driven
  /// instrument stays with its device (false).
  bool takeOver(int i, double t);
  /// The hinge of a taken-over instrument to `hinge` (m) at time t (through a trocar, the hand to
  /// its mirror), and its jaws closing or opening (at 5 per second) from t on.
  void steer(int i, const Vec3& hinge, double t);
  void moveJaws(int i, bool close, double t);
  /// Turns the needle taken-over instrument i holds about its own centre and normal by `angle`
  /// (rad; > 0 drives it towards its tip) over [t, t + duration] (Instrument::turnAbout); false,
  /// doing nothing, when i holds no needle, is not the hand's, or works through a trocar.
  bool turnNeedle(int i, double angle, double t, double duration = 0.2);
  /// The device of instrument i, or nullptr for a scripted one.
  HapticSession* device(int i) const { return devices_[i].get(); }
  /// haptics_<name>.csv per device-driven instrument in `directory`; one summary line each.
  std::string writeDeviceLogs(const std::string& directory) const;

  void beforeStep(Scene& scene);
  void afterStep(const Scene& scene);

  int size() const { return static_cast<int>(instruments_.size()); }
  int needleCount() const { return static_cast<int>(needles_.size()); }
  const Needle& needle(int k) const { return *needles_[k]; }
  const Instrument& instrument(int i) const { return *instruments_[i]; }
  /// The scene's wound, or nullptr.
  const Wound* wound() const { return wound_.get(); }
  const TraineeMetrics& metrics() const { return metrics_; }

  /// Whether s lies in a span of `body` coagulated by bipolar forceps.
  bool coagulated(const CurveBody& body, double s) const;

  /// What happened, one line per event ("t = 0.512 s: 'right' grasped 'thread' at s = 0.4").
  const std::vector<std::string>& events() const { return events_; }

  /// metrics.csv from now on: time, then per instrument tip x y z (m), jaw, speed (m/s), force on
  /// tissue (N), holding (0/1); one row per step. Throws std::runtime_error when it cannot open.
  void openCsv(const std::string& path);
  /// metrics.json (summary and events; with `knots`, not null, under "knots": the run's knot
  /// types at its last frame, which the run's output classifies).
  void writeSummary(const std::string& path, const nlohmann::json& knots = nullptr) const;

  /// The coupling force the hold of instrument i exerts on its thread at the scene's state (N;
  /// zero when it holds nothing).
  Vec3 holdForce(int i, const Scene& scene) const;

 private:
  InstrumentSet() = default;
  struct Span {
    const CurveBody* body;
    double from, to;
  };
  void attach(Scene& scene, const std::string& source);
  /// The jaws of instrument i closed on the thread between them (or on air).
  void closeJaws(int i, Scene& scene);
  void cut(int i, Scene& scene, const JawCatch& c);
  /// A grasper's thread slipping through its jaws (spring–slider, instrument.hpp).
  void slip(int i, const Scene& scene, const Vec3& force);
  void coagulate(int i, const Scene& scene);
  /// Tells every holding instrument which piece of its thread lies in its jaws (Instrument::setHeldSpan).
  void setHeldSpans(const Scene& scene);
  /// |Σ contact forces on instrument i's parts| at the scene's state (N).
  double partsForce(int i, const Scene& scene) const;
  void countToolContacts(double t);
  void event(double t, const std::string& what);

  std::vector<std::unique_ptr<Instrument>> instruments_;
  std::vector<std::unique_ptr<HapticSession>> devices_;   // per instrument; null: scripted
  std::vector<std::unique_ptr<Needle>> needles_;
  std::unique_ptr<Wound> wound_;
  /// A needle holder's jaws closed on a needle's wire: takes it (true), else false.
  bool catchNeedle(int i, double t);
  /// The needles where their holders have them over the coming step.
  void moveNeedles(double t);
  /// The threads' contact force on instrument i's parts (N; the reaction of partsForce's).
  Vec3 contactOnParts(int i, const Scene& scene) const;
  std::vector<std::vector<ToolForceField*>> fields_;       // per instrument, one per curve body
  std::vector<std::vector<const CurveBody*>> released_;   // per instrument: bodies it let go of
  std::vector<char> coagulating_done_;                    // per instrument: this hold coagulated
  std::vector<Span> coagulated_;
  /// Per instrument: the strand its held point was last found on, and the scene's layout then
  /// (found again only when the layout, the body or the strand changed: finding it allocates).
  struct HeldStrand {
    const CurveBody* body = nullptr;
    long revision = -1;
    Strand strand;
  };
  std::vector<HeldStrand> held_strands_;
  /// The strand of instrument i's held point s on `body`, from held_strands_, found again only
  /// when it is stale (another body, a layout change, or s outside it).
  const Strand& heldStrand(int i, const Scene& scene, const CurveBody* body, double s);
  std::vector<char> touching_;                            // per instrument pair: parts in contact
  TraineeMetrics metrics_;
  std::vector<std::string> events_;
  std::ofstream csv_;
  double dt_ = 1e-3;
  std::size_t ruptures_seen_ = 0;  // Scene::ruptures() already counted
  // The specimen ("metrics": {"specimen"}): the body, its kept end, and its strands as of the
  // body's layout revision seen last.
  const CurveBody* specimen_ = nullptr;
  double specimen_kept_end_ = 0.0;
  std::vector<Strand> specimen_strands_;
  long specimen_revision_ = -1;
  /// The specimen's length at the scene's state (m): the strands cut off the kept end, by chords.
  void measureSpecimen(const Scene& scene);
  // "inspection": the body and how much of it passed between the graspers.
  const CurveBody* inspected_ = nullptr;
  double inspection_step_ = 0.1;
  std::unique_ptr<GraspCoverage> coverage_;
};

}  // namespace filum::haptics
