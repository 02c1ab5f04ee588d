#include "filum/run_output.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/knot_determinant.hpp"
#include "filum/collision/knot_type.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/geometry/spline_point_mapping.hpp"

namespace filum::app {

namespace {

std::string exact(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", x);
  return buffer;
}

/// The abscissas knot.csv samples a strand at, whatever the output's curve_samples: the
/// breakpoints of the basis and, on curved bases (degree >= 2), kKnotSamplesPerSpan − 1 more in
/// each span (refined spans get theirs too); a polyline's vertices are the curve itself. A
/// polyline with chords of length l keeps within κ l² / 8 of the curve, and two strands of a
/// thread in contact with itself stay about 2r apart, so the polyline has the curve's crossings
/// when κ l² / 8 < r: with 4 samples a span of spacing h, when κ_max h² / 128 < r. A heuristic,
/// not a bound: it holds for loops down to a radius of h² / (128 r) (knot.json: 1 mm spans,
/// r = 0.15 mm, loops down to 0.05 mm, far tighter than the thread can lie), not for strands that
/// pass through each other (no self-collision).
constexpr int kKnotSamplesPerSpan = 4;

std::vector<double> knotAbscissas(const CurveBasis& basis, const Strand& strand) {
  const int per_span = basis.degree() >= 2 ? kKnotSamplesPerSpan : 1;
  std::vector<double> abscissas;
  const std::vector<double> breaks = basis.breakpoints();
  for (std::size_t i = 0; i + 1 < breaks.size(); ++i) {
    const double a = breaks[i], b = breaks[i + 1];
    if (a < strand.begin || b > strand.end || b <= a) continue;
    for (int k = 0; k < per_span; ++k) abscissas.push_back(a + (b - a) * k / per_span);
  }
  abscissas.push_back(strand.end);
  return abscissas;
}

/// The strand's points at `abscissas` (in [strand.begin, strand.end]), with them as scalars.
visual::PolyLine sampleStrand(const MechanicalState& body, const Strand& strand, std::vector<double> abscissas,
                              const SceneState& s, const std::string& t) {
  visual::PolyLine line{body.node()->path(), Points(abscissas.size(), 3), abscissas};
  geometry::SplinePointMapping(body.curve()->basis(), std::move(abscissas), strand).apply(body.block(s.q), line.points);
  if (!line.points.allFinite())
    throw NonFiniteFrame("refusing to write the non-finite curve of " + body.describe() + " at t = " + t + " s");
  return line;
}

/// `count` points of the strand at equal steps of s.
visual::PolyLine sampleStrand(const MechanicalState& body, const Strand& strand, int count, const SceneState& s,
                              const std::string& t) {
  std::vector<double> abscissas = geometry::uniformAbscissas(count);
  if (strand.begin != 0.0 || strand.end != 1.0)  // a strand of a cut curve: its own range of s
    for (double& a : abscissas) a = strand.begin + (strand.end - strand.begin) * a;
  return sampleStrand(body, strand, std::move(abscissas), s, t);
}

std::ofstream openCsv(const std::string& path, const char* header) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path + ": cannot open for writing");
  out << header << '\n';
  return out;
}

}  // namespace

RunOutput::RunOutput(const std::string& directory, int curve_samples, bool knots)
    : directory_(directory), curve_samples_(curve_samples), series_(directory + "/curve.pvd") {
  std::filesystem::create_directories(directory_ + "/vtk");
  control_points_ = openCsv(directory_ + "/control_points.csv", "time,body,index,x,y,z");
  curve_ = openCsv(directory_ + "/curve.csv", "time,body,sample,s,x,y,z");
  energy_ = openCsv(directory_ + "/energy.csv", "time,kinetic,potential,total,max_violation");
  if (knots)
    knots_ = openCsv(directory_ + "/knot.csv",
                     "time,body,strand,type,throws,crossings,jones,loop_length,contacts,contact_force,slip_speed");
}

void RunOutput::writeFrame(const Scene& scene) {
  const SceneState& s = scene.state();
  const std::string t = exact(s.time);
  if (!s.allFinite()) throw NonFiniteFrame("refusing to write a non-finite state at t = " + t + " s");
  // Everything of the frame is computed and checked first: a frame is written whole or not at
  // all, and no file ever holds a non-finite value (finite control points near 1e308 can still
  // give infinite curve points or energies).
  // One polyline per strand of every curve body (one for an uncut curve, CurveBasis::strands),
  // its samples at equal steps of s, in proportion to its share of [0, 1] (at least 2).
  // knot.csv classifies polylines of its own (knotAbscissas): the output's may be too coarse to
  // resolve a knot.
  std::vector<visual::PolyLine> lines, knot_lines;
  std::vector<const MechanicalState*> line_body;
  for (const MechanicalState* body : scene.bodies()) {
    const auto* spline = body->curve();
    if (!spline) continue;
    for (const Strand& strand : strands(spline->basis())) {
      const int count = std::max(2, static_cast<int>(std::lround(curve_samples_ * (strand.end - strand.begin))));
      lines.push_back(sampleStrand(*body, strand, count, s, t));
      line_body.push_back(body);
      if (knots_.is_open()) {
        knot_lines.push_back(sampleStrand(*body, strand, knotAbscissas(spline->basis(), strand), s, t));
      }
    }
  }
  const Energy e = scene.energy(s);
  const VecX g = scene.constraintViolation(s);
  const double violation = g.size() ? g.cwiseAbs().maxCoeff() : 0.0;
  if (!std::isfinite(e.kinetic) || !std::isfinite(e.potential) || !std::isfinite(e.total()) || !std::isfinite(violation))
    throw NonFiniteFrame("refusing to write a non-finite energy or constraint violation at t = " + t +
                         " s (kinetic " + exact(e.kinetic) + " J, potential " + exact(e.potential) + " J, violation " +
                         exact(violation) + ")");

  if (knots_.is_open()) classifyKnots(scene, knot_lines, line_body, t);

  std::size_t line_index = 0;
  for (const MechanicalState* body : scene.bodies()) {
    const std::string name = body->node()->path();
    const ConstPointsMap q = body->block(s.q);
    for (int i = 0; i < q.rows(); ++i)
      control_points_ << t << ',' << name << ',' << i << ',' << exact(q(i, 0)) << ',' << exact(q(i, 1)) << ','
                      << exact(q(i, 2)) << '\n';
    // The samples of the body's strands in order, numbered on (a cut's abscissa appears twice:
    // the end of one strand and the start of the next).
    for (int k = 0; line_index < lines.size() && line_body[line_index] == body; ++line_index) {
      const visual::PolyLine& line = lines[line_index];
      for (int j = 0; j < line.points.rows(); ++j, ++k)
        curve_ << t << ',' << name << ',' << k << ',' << exact(line.scalars[j]) << ',' << exact(line.points(j, 0)) << ','
               << exact(line.points(j, 1)) << ',' << exact(line.points(j, 2)) << '\n';
    }
  }
  energy_ << t << ',' << exact(e.kinetic) << ',' << exact(e.potential) << ',' << exact(e.total()) << ','
          << exact(violation) << '\n';
  if (!scene.layoutControllers().empty()) {
    if (!layout_.is_open()) layout_ = openCsv(directory_ + "/layout.csv", "time,body,points,inserted,removed");
    for (const MechanicalState* body : scene.bodies())
      layout_ << t << ',' << body->node()->path() << ',' << body->pointCount() << ',' << scene.adaptiveInsertions()
              << ',' << scene.adaptiveRemovals() << '\n';
    flushOrThrow(layout_, "layout.csv");
  }
  if (knots_.is_open()) {
    for (const KnotRow& k : knot_rows_)
      knots_ << t << ',' << k.body << ',' << k.strand << ',' << k.type << ',' << k.throws << ',' << k.crossings << ',' << k.jones << ','
             << exact(k.tightness.loop_length) << ',' << k.tightness.contacts << ',' << exact(k.tightness.contact_force)
             << ',' << exact(k.tightness.slip_speed) << '\n';
    flushOrThrow(knots_, "knot.csv");
  }

  char file[64];
  std::snprintf(file, sizeof file, "vtk/curve_%06d.vtp", frame_);
  visual::writeVtp(directory_ + "/" + file, lines, "abscissa");
  series_.add(s.time, file);
  flushOrThrow(control_points_, "control_points.csv");
  flushOrThrow(curve_, "curve.csv");
  flushOrThrow(energy_, "energy.csv");
  ++frame_;
}

void RunOutput::classifyKnots(const Scene& scene, const std::vector<visual::PolyLine>& lines,
                              const std::vector<const MechanicalState*>& line_body, const std::string& t) {
  // Each strand closed far away; diagrams of more than 16 crossings are left "unknown" (the
  // state sum costs 2ⁿ: 16 keeps a frame within milliseconds).
  constexpr int kFrameCrossings = 16;
  const auto* pipeline = dynamic_cast<const collision::ContactPipeline*>(scene.collisionPipeline());
  // The rows are built aside and kept only when all are finite: knotText and knotSummary never
  // report a frame that was not written.
  std::vector<KnotRow> rows;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    KnotRow row;
    row.body = lines[i].name;
    row.strand = i > 0 && line_body[i - 1] == line_body[i] ? rows.back().strand + 1 : 0;
    const collision::KnotType k = collision::knotType(collision::closeFarAway(lines[i].points), kFrameCrossings);
    row.name = k.name;
    row.type = k.name + (k.mirrored ? " (mirror)" : "");
    row.throws = collision::throwsString(k.throws);
    row.crossings = k.crossings;
    row.jones = collision::toString(k.jones);
    row.tightness = collision::knotTightness(pipeline, *line_body[i]->curve(), lines[i].scalars,
                                             collision::knotSpan(k, static_cast<int>(lines[i].points.rows())), scene.state());
    if (!row.tightness.allFinite())
      throw NonFiniteFrame("refusing to write the non-finite knot tightness of " + line_body[i]->describe() + " at t = " +
                           t + " s");
    rows.push_back(std::move(row));
  }
  knot_rows_ = std::move(rows);
}

void RunOutput::flushOrThrow(std::ofstream& out, const char* name) const {
  out.flush();
  if (!out) throw std::runtime_error(directory_ + "/" + name + ": write failed (disk full or file size limit?)");
}

nlohmann::json RunOutput::knotSummary() const {
  nlohmann::json rows = nlohmann::json::array();
  for (const KnotRow& k : knot_rows_)
    rows.push_back({{"body", k.body},
                    {"strand", k.strand},
                    {"type", k.type},
                    {"throws", k.throws},
                    {"crossings", k.crossings},
                    {"loop_length", k.tightness.loop_length},
                    {"contacts", k.tightness.contacts},
                    {"contact_force", k.tightness.contact_force},
                    {"slip_speed", k.tightness.slip_speed}});
  return rows;
}

std::string RunOutput::knotText() const {
  // "thread: square, 2.9 cm held, 5 contacts 0.05 N, slip 0.4 mm/s" per knotted strand.
  std::string text;
  for (const KnotRow& k : knot_rows_) {
    if (k.name == "unknot" || k.name == "unknown") continue;
    char strand[32] = "";
    if (k.strand > 0) std::snprintf(strand, sizeof strand, " (strand %d)", k.strand);
    char line[200];
    std::snprintf(line, sizeof line, "%s%s%s: %s, %.1f cm held, %d contacts %.2f N, slip %.1f mm/s", text.empty() ? "" : "; ",
                  k.body.c_str(), strand, k.type.c_str(), 100.0 * k.tightness.loop_length, k.tightness.contacts,
                  k.tightness.contact_force, 1000.0 * k.tightness.slip_speed);
    text += line;
  }
  return text;
}

}  // namespace filum::app
