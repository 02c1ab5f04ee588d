// RunOutput: what `filum run` writes into its output folder, frame by frame:
//   control_points.csv  time, body, index, x, y, z            (the DOFs)
//   curve.csv           time, body, sample, s, x, y, z         (P(s) at equal parametric spacing)
//   energy.csv          time, kinetic, potential, total, max_violation
//   vtk/curve_NNNNNN.vtp + curve.pvd                           (ParaView plays the run)
// Every file is flushed after each frame, so a run that stops early leaves complete frames.
// Numbers are written with 17 significant digits (exact, comparable bit for bit).
#pragma once

#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "filum/collision/knot_tightness.hpp"
#include "filum/core/scene.hpp"
#include "filum/visual/vtp_writer.hpp"

namespace filum::app {

/// A frame that holds a non-finite value: nothing of it was written (the run diverged).
class NonFiniteFrame : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class RunOutput {
 public:
  /// Creates `directory` (and vtk/ inside). curve_samples >= 2.
  /// knots: also knot.csv (time, body, strand, type, throws, crossings, jones, loop_length, contacts,
  /// contact_force, slip_speed): each strand of each thread closed far away and classified
  /// (collision/knot_type.hpp), its knot's tightness and slip (collision/knot_tightness.hpp), at
  /// every frame.
  RunOutput(const std::string& directory, int curve_samples, bool knots = true);

  /// Writes one frame of the scene's current state (and, when the scene changes its points as it
  /// runs — layout controllers, adaptive refinement — layout.csv: time, body, control points,
  /// and the insertions and removals of the scene so far). Throws NonFiniteFrame (and writes nothing)
  /// if a value is not finite, std::runtime_error naming the file if a write fails.
  void writeFrame(const Scene& scene);
  int frames() const { return frame_; }
  /// The knotted strands of the last frame for a heads-up display ("" when none is knotted or
  /// knots are off): body, type, thread held, contacts and their force, slip speed.
  std::string knotText() const;
  /// The last frame's knot rows for metrics.json: per strand, its type, throws, crossings and
  /// tightness (an empty array when knot.csv is off).
  nlohmann::json knotSummary() const;
  const std::string& directory() const { return directory_; }

 private:
  void flushOrThrow(std::ofstream& out, const char* name) const;

  std::string directory_;
  int curve_samples_;
  int frame_ = 0;
  /// One row of knot.csv.
  struct KnotRow {
    std::string body;
    int strand = 0;
    std::string name, type;  // the table's name; with " (mirror)" when it matched the mirror image
    std::string throws;      // "+2 -1": the signed wraps of each throw (collision::throwsString)
    int crossings = -1;
    std::string jones;
    collision::KnotTightness tightness;
  };
  /// The knot rows of a frame (thrown NonFiniteFrame when a value is not finite).
  void classifyKnots(const Scene& scene, const std::vector<visual::PolyLine>& lines,
                     const std::vector<const MechanicalState*>& line_body, const std::string& t);
  std::vector<KnotRow> knot_rows_;  // the last frame's strands
  std::ofstream control_points_, curve_, energy_, knots_, layout_;
  visual::PvdSeries series_;
};

}  // namespace filum::app
