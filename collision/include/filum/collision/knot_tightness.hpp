// KnotTightness: how much thread a tied knot holds, how hard its strands press on each other and
// whether they slip — what a surgeon feels when a knot is snugged down, and what tells a knot
// that is being tightened from one that is running (a granny slipping under load).
//
//   loop length     the arc length of the thread between the first and last crossing passage of
//                   the knot's diagram (KnotSpan): the thread the knot holds. It falls as the
//                   knot is tightened (knot.json: 4.5 cm loose, 2.9 cm snug, 1.7 cm after a pull);
//   contacts        the contacts of the thread with itself whose two points both lie in that
//                   span, and the sum of their force magnitudes |F| (N, the multipliers of the
//                   last solve or the penalty: ContactPipeline::contactForce);
//   slip speed      the largest tangential relative speed at those contacts,
//                     |(I − n nᵀ)(v_A − v_B)|   (m/s),
//                   zero for a knot that holds (sticking contacts move together) and for any rigid
//                   translation of the knot; the speed at which thread runs through a slipping one.
// Every quantity is measured on the contact set of the last step (detected at its start, forces
// of its solve) and the state after it.
#pragma once

#include <vector>

#include "filum/collision/contact_pipeline.hpp"
#include "filum/collision/knot_type.hpp"
#include "filum/core/curve_body.hpp"

namespace filum::collision {

struct KnotTightness {
  double loop_length = 0.0;    // m
  int contacts = 0;            // self-contacts with both points in the knot
  double contact_force = 0.0;  // N, Σ |F| over them
  double slip_speed = 0.0;     // m/s, max over them
};

/// Arc length of a polyline between two positions (vertex index + fraction of the next edge).
double polylineLength(const Points& line, double from, double to);

/// The value at a polyline position of per-vertex values (the abscissa of each vertex: linear
/// along each edge).
double atPosition(const std::vector<double>& values, double position);

/// The tightness of the knot held in `span` of `line` (the polyline of `body` whose vertices
/// have the abscissas `abscissas`), from the pipeline's contacts (null: no contacts) at state s.
/// All zero when the span is not found.
KnotTightness knotTightness(const ContactPipeline* pipeline, const CurveBody& body, const Points& line,
                            const std::vector<double>& abscissas, const KnotSpan& span, const SceneState& s);

}  // namespace filum::collision
