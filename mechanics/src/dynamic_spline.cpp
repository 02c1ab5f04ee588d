#include "filum/mechanics/dynamic_spline.hpp"

#include <cmath>
#include <limits>
#include <numbers>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/bspline_curve.hpp"
#include "filum/geometry/curve_splitting.hpp"
#include "filum/geometry/gauss_legendre.hpp"
#include "filum/geometry/knot_insertion.hpp"
#include "filum/geometry/knot_removal.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/geometry/spline_basis_factory.hpp"
#include "filum/geometry/uniform_cubic_bspline.hpp"
#include "filum/mechanics/mass_matrix.hpp"

namespace filum::mechanics {

namespace {
const char* const kControlPointLimit =
    "dynamic_spline.hpp: memory and step time grow with the count; 600 times the largest reference body, rope.json's 165";
}  // namespace

DynamicSpline::DynamicSpline(std::unique_ptr<CurveBasis> basis, Points initial, double mass,
                             double radius)
    : basis_(std::move(basis)),
      initial_(std::move(initial)),
      mass_(mass),
      radius_(radius),
      rest_length_(arcLength(*basis_, initial_)),
      mass_matrix_(mechanics::massMatrix(*basis_, mass)),
      mass_band_(mass_matrix_, basis_->degree()),
      factor_(mass_matrix_, basis_->degree()),
      basis_integrals_(basisIntegrals(*basis_)) {}

void DynamicSpline::initialVelocities(PointsRef v) const {
  if (initial_velocities_.rows() == 0)
    v.setZero();
  else
    v = initial_velocities_;
}

void DynamicSpline::setInitialVelocities(Points velocities) {
  if (velocities.rows() != initial_.rows())
    throw std::invalid_argument("DynamicSpline::setInitialVelocities: " + std::to_string(velocities.rows()) +
                                " velocities for " + std::to_string(initial_.rows()) + " control points");
  initial_velocities_ = std::move(velocities);
}

geometry::BSplineCurve DynamicSpline::knotForm() const {
  // Only a B-spline's control points are those of its knot form (Catmull-Rom's are not).
  try {
    if (basis_->name() == "catmull_rom") throw std::invalid_argument("");
    return geometry::toBSplineCurve(*basis_, initial_);
  } catch (const std::invalid_argument&) {
    throw SceneError(origin(), "a B-spline basis (uniform_cubic_bspline or a NUBS) to insert, remove or cut control points",
                     "the " + basis_->name() + " basis of " + describe());
  }
}

void DynamicSpline::adopt(int degree, std::vector<double> knots, const SparseMatrix& R) {
  basis_ = std::make_unique<geometry::NonUniformBSpline>(degree, std::move(knots));
  initial_ = R * initial_;  // the rest shape, mapped like any configuration
  if (initial_velocities_.rows() > 0) initial_velocities_ = R * initial_velocities_;  // Ṗ = Σ b_i q̇_i: the same map
  mass_matrix_ = mechanics::massMatrix(*basis_, mass_);
  mass_band_ = ScalarBand(mass_matrix_, basis_->degree());
  factor_ = BandedCholesky(mass_matrix_, basis_->degree());
  basis_integrals_ = basisIntegrals(*basis_);
  noteLayoutChange();
}

namespace {

/// The limit of control points after `inserted` insertions into `count`: what a message expects
/// (empty when within it) and what it found.
struct InsertionLimit {
  std::string expected, found;
};
InsertionLimit insertionLimit(int count, std::size_t inserted) {
  if (inserted <= static_cast<std::size_t>(kMaxControlPoints - count)) return {};
  return {"at most " + std::to_string(kMaxControlPoints) + " control points after the insertions (" +
              kControlPointLimit + ")",
          std::to_string(count) + " + " + std::to_string(inserted)};
}

}  // namespace

SparseMatrix DynamicSpline::refine(const std::vector<double>& abscissas) {
  if (const InsertionLimit limit = insertionLimit(pointCount(), abscissas.size()); !limit.expected.empty())
    throw SceneError(origin(), limit.expected, limit.found);
  const geometry::BSplineCurve curve = knotForm();
  // s ∈ [0, 1] maps affinely onto the knot domain [t_d, t_n] (bspline_curve.hpp).
  const double u0 = curve.knots[curve.degree], u1 = curve.knots[pointCount()];
  std::vector<double> new_knots;
  new_knots.reserve(abscissas.size());
  for (const double s : abscissas) {
    if (!(s > 0.0 && s < 1.0))
      throw SceneError(origin(), "abscissas strictly inside (0, 1) to insert control points at", std::to_string(s));
    new_knots.push_back(u0 + s * (u1 - u0));
  }
  std::vector<double> refined;
  try {
    refined = geometry::refinedKnotVector(curve.degree, curve.knots, new_knots);
  } catch (const std::invalid_argument& e) {
    throw SceneError(origin(), "knots that keep the curve valid (multiplicity <= degree + 1: a cut at most)", e.what());
  }
  SparseMatrix A = geometry::knotInsertionMatrix(curve.degree, curve.knots, refined);
  adopt(curve.degree, std::move(refined), A);
  return A;
}

SparseMatrix DynamicSpline::cut(double abscissa) {
  if (!(abscissa > 0.0 && abscissa < 1.0))
    throw SceneError(origin(), "an abscissa strictly inside (0, 1) to cut " + describe() + " at", std::to_string(abscissa));
  // Snapped as splitCurve snaps (8 ulps of the domain): a cut already there is refused.
  for (const double c : basis_->cuts())
    if (std::abs(c - abscissa) <= 8.0 * std::numeric_limits<double>::epsilon())
      throw SceneError(origin(), "an abscissa where " + describe() + " is not cut yet", std::to_string(abscissa));
  const int d = basis_->degree();
  if (const InsertionLimit limit = insertionLimit(pointCount(), static_cast<std::size_t>(d + 1)); !limit.expected.empty())
    throw SceneError(origin(), limit.expected, limit.found);
  // The knot raised to multiplicity d + 1 (geometry/curve_splitting.hpp, exact): the knot
  // vector of the whole body is the first strand's followed by the second's after its d + 1
  // copies of u, and A is the Oslo refinement onto it.
  geometry::SplitCurve split;
  try {
    split = geometry::splitCurve(knotForm(), abscissa);
  } catch (const std::invalid_argument& e) {
    throw SceneError(origin(), "a cut that leaves a valid curve on either side", e.what());
  }
  std::vector<double> knots = split.before.knots;
  knots.insert(knots.end(), split.after.knots.begin() + d + 1, split.after.knots.end());
  adopt(d, std::move(knots), split.refinement);
  return split.refinement;
}

SparseMatrix DynamicSpline::coarsen(double abscissa, ConstPointsRef q, double tolerance) {
  const geometry::BSplineCurve rest = knotForm();
  const int d = rest.degree, n = pointCount();
  const double u0 = rest.knots[d], u1 = rest.knots[n];
  // The interior knot nearest to u(s); it must be that knot to round-off of the map s → u.
  const double u = u0 + abscissa * (u1 - u0);
  double knot = 0.0, gap = std::numeric_limits<double>::infinity();
  for (int i = d + 1; i < n; ++i)
    if (std::abs(rest.knots[i] - u) < gap) gap = std::abs(rest.knots[i] - u), knot = rest.knots[i];
  if (!(gap <= 1e-12 * (u1 - u0)))
    throw SceneError(origin(), "the abscissa of an interior knot of " + describe() + " to remove",
                     std::to_string(abscissa));
  // R column by column: removeKnot is linear in the points (fixed rows, least squares on the
  // d − 1 points around the knot), so it maps unit points e_j to column j of R.
  geometry::BSplineCurve unit{d, rest.knots, Points::Zero(n, 3)};
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> coarse_knots;
  for (int j = 0; j < n; j += 3) {
    unit.control_points.setZero();
    for (int c = 0; c < 3 && j + c < n; ++c) unit.control_points(j + c, c) = 1.0;
    const geometry::KnotRemoval removal = geometry::removeKnot(unit, knot);
    const Points& p = removal.curve.control_points;
    for (int i = 0; i < p.rows(); ++i)
      for (int c = 0; c < 3 && j + c < n; ++c)
        if (p(i, c) != 0.0) entries.emplace_back(i, j + c, p(i, c));
    coarse_knots = removal.curve.knots;
  }
  SparseMatrix R(n - 1, n);
  R.setFromTriplets(entries.begin(), entries.end());
  // How far the curve moves, for the state and for the rest shape (convex-hull bound).
  const double moved = std::max(geometry::removeKnot(geometry::BSplineCurve{d, rest.knots, Points(q)}, knot).error_bound,
                                geometry::removeKnot(rest, knot).error_bound);
  if (!(moved <= tolerance)) return SparseMatrix();
  adopt(d, std::move(coarse_knots), R);
  return R;
}

void DynamicSpline::addGravity(const Vec3& g, PointsRef B) const {
  // Q_i = ∫ b_i(s) m g ds = m w_i g  (right-hand side of paper eq. 2).
  for (int i = 0; i < pointCount(); ++i) B.row(i) += (mass_ * basis_integrals_[i]) * g.transpose();
}

void DynamicSpline::addMassMatrix(double factor, JacobianAccumulator& out) const {
  // (M ⊗ I₃)_(3i+α, 3j+α) = M_ij: the same block for x, y and z (paper eq. 3).
  const int base = offset();
  for (int i = 0; i < mass_matrix_.outerSize(); ++i)
    for (SparseMatrix::InnerIterator it(mass_matrix_, i); it; ++it)
      out.addIsotropic(base + i, base + static_cast<int>(it.col()), factor * it.value());
}

double DynamicSpline::gravityPotential(const Vec3& g, ConstPointsRef q) const {
  // V = −∫ m g·P(s) ds = −Σ_i m w_i g·q_i
  double v = 0.0;
  for (int i = 0; i < pointCount(); ++i) v -= mass_ * basis_integrals_[i] * g.dot(q.row(i).transpose());
  return v;
}

double arcLength(const CurveBasis& basis, ConstPointsRef q, int nodes_per_piece) {
  const geometry::QuadratureRule rule = geometry::gaussLegendre(nodes_per_piece);
  const std::vector<double> pieces = basis.breakpoints();
  geometry::BasisRow row;
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < pieces.size(); ++k)
    length += geometry::integrate(rule, pieces[k], pieces[k + 1], [&](double s) {
      basis.evaluate(s, row);
      return geometry::curveTangent(row, q).norm();
    });
  return length;
}

std::unique_ptr<CurveBasis> makeBasis(const Params& p, const std::string& key, int control_points) {
  const std::string name = p.string(key, "uniform_cubic_bspline");
  geometry::SplineBasisSpec spec;
  spec.name = name;
  spec.control_points = control_points;
  if (name == "uniform_cubic_bspline" || name == "catmull_rom") {
    if (control_points < 4)
      p.fail("control_points",
             std::string("at least 4 control points for a ") +
                 (name == "catmull_rom" ? "Catmull-Rom spline" : "uniform cubic B-spline"),
             std::to_string(control_points));
  } else if (name == "nubs") {
    // Degree 2 to 5: a degree-1 curve has no curvature for the bending energies to see.
    spec.degree = p.integer("degree", 2, 5, 3, "a NUBS of degree 2 to 5");
    spec.clamped = p.boolean("clamped", true);
    if (p.has("knots")) {
      const nlohmann::json& knots = p.raw({"knots", "1"});
      if (!knots.is_array() || knots.size() != static_cast<std::size_t>(control_points + spec.degree + 1))
        p.fail("knots", "a list of n + degree + 1 = " + std::to_string(control_points + spec.degree + 1) +
                            " non-decreasing knots", describeJson(knots));
      for (const auto& k : knots) {
        if (!k.is_number()) p.fail("knots", "numbers", describeJson(k));
        spec.knots.push_back(k.get<double>());
      }
    }
    if (control_points < spec.degree + 1)
      p.fail("control_points", "at least degree + 1 = " + std::to_string(spec.degree + 1) + " control points for a NUBS",
             std::to_string(control_points));
  } else {
    p.fail(key, "a known basis (uniform_cubic_bspline, catmull_rom, nubs)", "\"" + name + "\"");
  }
  try {
    return geometry::makeSplineBasis(spec);
  } catch (const std::invalid_argument& e) {
    p.fail(spec.knots.empty() ? key : "knots", "a valid knot vector", e.what());
  }
}

namespace {

// The messages below write the limits out, as people read them.
static_assert(kMaxCoordinate == 1e6 && kMaxSpeed == 1e6, "the messages say ±1e6 m and ±1e6 m/s: change them too");

void checkCoordinates(const Params& p, const std::string& key, const Vec3& x) {
  if (x.cwiseAbs().maxCoeff() > kMaxCoordinate)
    p.fail(key, "coordinates within ±1e6 m (dynamic_spline.hpp: scenes are in metres; beyond, squared lengths and "
                "energies approach overflow)");
}

Points controlPointList(const Params& p) {
  const Points q = p.points({"control_points", "m"}, 1, kMaxControlPoints, kControlPointLimit);
  for (Eigen::Index i = 0; i < q.rows(); ++i)
    if (q.row(i).cwiseAbs().maxCoeff() > kMaxCoordinate)
      p.fail("control_points", "control points within ±1e6 m of the origin (dynamic_spline.hpp: scenes are in metres; "
                               "beyond, squared lengths and energies approach overflow)",
             "point " + std::to_string(i) + " at " + describeJson(p.raw({"control_points", "m"})[i]));
  return q;
}

// "velocities": one per control point, each component within ±kMaxSpeed.
Points velocityList(const Params& p, int count) {
  const Points v = p.points({"velocities", "m/s"}, count, count,
                            "dynamic_spline.hpp: one velocity per control point, " + std::to_string(count) + " here");
  for (Eigen::Index i = 0; i < v.rows(); ++i)
    if (v.row(i).cwiseAbs().maxCoeff() > kMaxSpeed)
      p.fail("velocities", "velocities within ±1e6 m/s (dynamic_spline.hpp: beyond, kinetic energies approach overflow)",
             "velocity " + std::to_string(i) + " " + describeJson(p.raw({"velocities", "m/s"})[i]));
  return v;
}

// The factored mass matrix M = m ∫ b_i b_j ds: a mass so small that M's pivots underflow is
// reported at the parameter that gave it, not as an abort.
std::unique_ptr<DynamicSpline> build(const Params& p, std::unique_ptr<CurveBasis> basis, Points q,
                                     double mass, double radius) {
  try {
    return std::make_unique<DynamicSpline>(std::move(basis), std::move(q), mass, radius);
  } catch (const std::runtime_error& e) {
    p.fail(p.has({"mass", "kg"}) ? "mass" : "density",
           "a mass whose matrix M = m ∫ b_i b_j ds is positive definite in double precision",
           describeJson(p.raw(p.has({"mass", "kg"}) ? "mass" : "density")) + ", total mass " + describeJson(mass) +
               " kg (" + e.what() + ")");
  }
}

/// The control point count of {"from", "to", "count"}: at least 4 (a cubic's support), or
/// degree + 1 for a NUBS (p: the DynamicSpline's parameters).
int straightThreadCount(const Params& p, const Params& line) {
  const int minimum = p.string("basis", "uniform_cubic_bspline") == "nubs"
                          ? p.integer("degree", 2, 5, 3, "a NUBS of degree 2 to 5") + 1
                          : 4;
  return line.integer("count", minimum, kMaxControlPoints, kControlPointLimit);
}

Points straightThread(const Params& line, const CurveBasis& basis, int n) {
  // A straight thread from `from` to `to`, uniformly parametrized (|P'| constant):
  //  - uniform cubic B-spline and Catmull-Rom: collinear, equally spaced control points
  //    q_i = from + (i − 1) h, h = (to − from)/(n − 3): the curve runs exactly from
  //    P(0) = q_1 = from to P(1) = q_{n−2} = to;
  //  - NUBS: q_i at the Greville abscissae ξ_i = (t_{i+1} + ... + t_{i+d})/d mapped to [0, 1]
  //    (a B-spline reproduces a linear function from its Greville points: P(s) = from + s (to − from)).
  const Vec3 from = line.vec3({"from", "m"});
  const Vec3 to = line.vec3({"to", "m"});
  checkCoordinates(line, "from", from);
  checkCoordinates(line, "to", to);
  if ((to - from).norm() == 0.0) line.fail("to", "a point different from 'from' (a thread of non-zero length)");
  line.finish();
  Points q(n, 3);
  if (const auto* nubs = dynamic_cast<const geometry::NonUniformBSpline*>(&basis)) {
    const std::vector<double>& t = nubs->knots();
    const int d = nubs->degree();
    const double a = nubs->domainStart(), b = nubs->domainEnd();
    for (int i = 0; i < n; ++i) {
      double xi = 0.0;
      for (int k = 1; k <= d; ++k) xi += t[i + k];
      q.row(i) = (from + ((xi / d - a) / (b - a)) * (to - from)).transpose();
    }
    return q;
  }
  const Vec3 h = (to - from) / (n - 3);
  for (int i = 0; i < n; ++i) q.row(i) = (from + (i - 1.0) * h).transpose();
  return q;
}

}  // namespace

double massFromParams(const Params& p, double radius, double length) {
  if (p.has({"mass", "kg"}) && p.has({"density", "kg/m³"})) p.fail("density", "either 'mass' or 'density', not both");
  if (p.has({"mass", "kg"})) return p.positive({"mass", "kg"});
  if (!p.has({"density", "kg/m³"})) p.fail("mass", "the body's 'mass' (kg) or its 'density' (kg/m³)");
  const double mass = p.positive({"density", "kg/m³"}) * std::numbers::pi * radius * radius * length;
  if (!(mass > 0.0) || !std::isfinite(mass))
    p.fail("density", "a density giving a positive, finite mass (ρ π r² L)",
           describeJson(p.raw({"density", "kg/m³"})) + ", mass " + describeJson(mass) + " kg");
  return mass;
}

std::unique_ptr<DynamicSpline> DynamicSpline::fromParams(const Params& p) {
  Points q;
  std::unique_ptr<CurveBasis> basis;
  if (p.has("control_points") && p.raw({"control_points", "m"}).is_object()) {
    const Params line = p.object("control_points");
    const int n = straightThreadCount(p, line);
    basis = makeBasis(p, "basis", n);
    q = straightThread(line, *basis, n);
  } else {
    q = controlPointList(p);
    basis = makeBasis(p, "basis", static_cast<int>(q.rows()));
  }
  const double radius = p.positive({"radius", "m"}, 1e-4);
  const double length = arcLength(*basis, q);
  if (!(length > 0.0) || !std::isfinite(length))
    p.fail("control_points", "control points that span a curve of finite, non-zero length",
           "length " + describeJson(length) + " m");
  auto spline = build(p, std::move(basis), std::move(q), massFromParams(p, radius, length), radius);
  if (p.has("velocities")) spline->setInitialVelocities(velocityList(p, spline->pointCount()));
  std::vector<CurveBody::LayoutChange> changes = CurveBody::layoutChangesFromParams(p);
  // Checked before anything is inserted: a cut adds at most degree + 1 points.
  std::size_t inserted = 0;
  for (const CurveBody::LayoutChange& c : changes)
    inserted += c.kind == CurveBody::LayoutChange::Kind::kCut ? spline->basis().degree() + 1 : c.abscissas.size();
  if (const InsertionLimit limit = insertionLimit(spline->pointCount(), inserted); !limit.expected.empty())
    p.fail(p.has("cuts") ? "cuts" : "refine", limit.expected, limit.found);
  spline->setLayoutChanges(std::move(changes));
  return spline;
}

}  // namespace filum::mechanics
