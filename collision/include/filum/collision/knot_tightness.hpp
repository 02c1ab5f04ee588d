// KnotTightness: how much thread a tied knot holds, how hard its strands press on each other and
// whether they slip — what a surgeon feels when a knot is snugged down, and what tells a knot
// that is being tightened from one that is running (a granny slipping under load).
//
//   loop length     the arc length of the thread's centre line between the first and last
//                   passage of the knot's self-crossings (KnotSpan): the thread the knot holds.
//                   It falls as the knot is drawn tight (knot.json: 4.8 cm loose, 2.9 cm at
//                   rest once tightened, 2.0 cm after the fast pull);
//   contacts        the contacts of the thread with itself whose two points both lie in that
//                   span and that press (a normal force n·F > 0: contacts kept within the
//                   detection margin but not touching carry no force and hold nothing), and the
//                   sum of their force magnitudes |F| (N, the multipliers of the last solve or the
//                   penalty: ContactPipeline::contactForce);
//   slip speed      the largest tangential relative speed of the centre-line points at those
//                   contacts,
//                     |(I − n nᵀ)(v_A − v_B)|   (m/s),
//                   zero for sticking contacts (the friction rows hold v_A − v_B along the
//                   tangents) and for any rigid translation of the knot; a knot turning as a
//                   whole at ω shows at most ω times the distance between the centre lines
//                   (2 r), as the friction rows see it. A slipping knot: the speed thread runs through it.
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
  int contacts = 0;            // pressed self-contacts with both points in the knot
  double contact_force = 0.0;  // N, Σ |F| over them
  double slip_speed = 0.0;     // m/s, max over them

  bool allFinite() const;
};

/// The value at a polyline position (vertex index + fraction of the next edge) of per-vertex
/// values, linear along each edge (the abscissa of each vertex of a sampled curve).
double atPosition(const std::vector<double>& values, double position);

/// The tightness of the knot held in `span` of the polyline whose vertices sample `body` at
/// `abscissas`, from the pipeline's contacts (null: no contacts) at state s. All zero when the
/// span is not found.
KnotTightness knotTightness(const ContactPipeline* pipeline, const CurveBody& body, const std::vector<double>& abscissas,
                            const KnotSpan& span, const SceneState& s);

}  // namespace filum::collision
