#include "filum/mechanics/framed_chain.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/nonuniform_bspline.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::mechanics {

namespace {

/// Segment i's quaternion in the frames' block of q (4 numbers per segment).
Eigen::Quaterniond quaternionAt(Eigen::Ref<const VecX> q, int segment) {
  return geometry::unpackQuaternion(q.data() + 4 * segment);
}

void store(const Eigen::Quaterniond& r, Eigen::Ref<VecX> q, int segment) {
  geometry::packQuaternion(r, q.data() + 4 * segment);
}

/// The degree-1 B-spline through the nodes, knots at their rest arc lengths (clamped).
std::unique_ptr<CurveBasis> polylineBasis(const std::vector<double>& lengths) {
  std::vector<double> knots{0.0, 0.0};
  double arc = 0.0;
  for (const double l : lengths) knots.push_back(arc += l);
  knots.push_back(arc);
  return std::make_unique<geometry::NonUniformBSpline>(1, std::move(knots));
}

}  // namespace

// (Each written as the disc's expression minus the lumen's, so that a solid section computes the
// same doubles as π r r and π r r r r / 4 did before tubes.)
double FramedChain::Section::area() const {
  return std::numbers::pi * radius * radius - std::numbers::pi * inner_radius * inner_radius;
}

double FramedChain::Section::secondMoment() const {
  const double disc = std::numbers::pi * radius * radius, lumen = std::numbers::pi * inner_radius * inner_radius;
  return (disc * radius * radius - lumen * inner_radius * inner_radius) / 4.0;
}

namespace {

/// Rest lengths of the segments between consecutive nodes.
std::vector<double> segmentLengths(const Points& nodes) {
  std::vector<double> lengths;
  for (Eigen::Index i = 0; i + 1 < nodes.rows(); ++i) lengths.push_back((nodes.row(i + 1) - nodes.row(i)).norm());
  return lengths;
}

/// "inner_radius" (m) of p, `fallback` when absent: in [0, radius) (a wall of non-zero thickness);
/// `radius_name` names the radius it must stay below in the refusal.
double innerRadiusFromParams(const Params& p, double radius, double fallback, const std::string& radius_name) {
  const double inner = p.nonNegative({"inner_radius", "m"}, fallback);
  if (!(inner < radius)) {
    const std::string expected = std::string("an inner radius (the lumen) below ").append(radius_name).append(" (")
                                     .append(describeJson(radius)).append(" m): a wall of non-zero thickness");
    if (p.has({"inner_radius", "m"})) p.fail("inner_radius", expected, describeJson(inner) + " m");
    p.fail("radius",
           std::string("a radius above the body's 'inner_radius' (").append(describeJson(inner))
               .append(" m), or an 'inner_radius' of its own below it"),
           describeJson(radius) + " m");
  }
  return inner;
}

double total(const std::vector<double>& values) {
  double sum = 0.0;
  for (const double v : values) sum += v;
  return sum;
}

}  // namespace

FramedChain::FramedChain(Points nodes, double radius, double mass)
    : FramedChain(nodes, radius,
                  std::vector<Section>(std::max<Eigen::Index>(nodes.rows() - 1, 0),
                                       {radius, mass / (std::numbers::pi * radius * radius * total(segmentLengths(nodes)))})) {}

FramedChain::FramedChain(Points nodes, double radius, std::vector<Section> sections)
    : nodes_(std::move(nodes)), radius_(radius), sections_(std::move(sections)) {
  const int n = pointCount();
  rest_lengths_ = segmentLengths(nodes_);
  const double length = total(rest_lengths_);
  basis_ = polylineBasis(rest_lengths_);
  // Per segment: ρA l shared half-half by its nodes; rotary inertia ρ l diag(I, I, 2I), with the
  // section's A and I (a disc's or a tube wall's, Section).
  masses_.assign(n, 0.0);
  mass_ = 0.0;
  double arc = 0.0;
  node_abscissas_.push_back(0.0);
  for (int i = 0; i + 1 < n; ++i) {
    const double l = rest_lengths_[i], segment_mass = sections_[i].density * sections_[i].area() * l;
    const double second = sections_[i].secondMoment();
    masses_[i] += 0.5 * segment_mass;
    masses_[i + 1] += 0.5 * segment_mass;
    mass_ += segment_mass;
    inertia_.push_back(sections_[i].density * l * Vec3(second, second, 2.0 * second));
    node_abscissas_.push_back((arc += l) / length);
  }
  node_abscissas_.back() = 1.0;
  hollow_ = !sections_.empty();
  for (const Section& section : sections_) {
    radius_varies_ = radius_varies_ || section.radius != radius_;
    hollow_ = hollow_ && section.inner_radius > 0.0;
    inner_radius_varies_ = inner_radius_varies_ || section.inner_radius != sections_.front().inner_radius;
  }
  Vec3 previous = Vec3::UnitZ();
  Eigen::Quaterniond frame = Eigen::Quaterniond::Identity();
  for (int i = 0; i + 1 < n; ++i) {
    const Vec3 tangent = (nodes_.row(i + 1) - nodes_.row(i)).transpose() / rest_lengths_[i];
    frame = (Eigen::Quaterniond::FromTwoVectors(previous, tangent) * frame).normalized();  // parallel transport
    initial_frames_.push_back(frame);
    previous = tangent;
  }
}

std::unique_ptr<FramedChain> FramedChain::fromParams(const Params& p) {
  Points nodes;
  if (p.has("nodes") && p.raw({"nodes", "m"}).is_object()) {
    const Params line = p.object("nodes");
    const Vec3 from = line.vec3({"from", "m"}), to = line.vec3({"to", "m"});
    const int n = line.integer("count", 2, kMaxControlPoints, "framed_chain.hpp: as many nodes as a spline's points");
    if ((to - from).norm() == 0.0) line.fail("to", "a point different from 'from' (a chain of non-zero length)");
    line.finish();
    nodes.resize(n, 3);
    for (int i = 0; i < n; ++i) nodes.row(i) = (from + (to - from) * (double(i) / (n - 1))).transpose();
  } else {
    nodes = p.points({"nodes", "m"}, 2, kMaxControlPoints, "framed_chain.hpp: as many nodes as a spline's points");
  }
  for (Eigen::Index i = 0; i < nodes.rows(); ++i) {
    if (nodes.row(i).cwiseAbs().maxCoeff() > kMaxCoordinate)
      p.fail("nodes", "nodes within ±1e6 m of the origin", "node " + std::to_string(i));
    if (i > 0 && (nodes.row(i) - nodes.row(i - 1)).norm() == 0.0)
      p.fail("nodes", "distinct consecutive nodes (segments of non-zero length)", "node " + std::to_string(i) + " repeats node " + std::to_string(i - 1));
  }
  const double radius = p.positive({"radius", "m"}, 1e-3);
  const double inner_radius = innerRadiusFromParams(p, radius, 0.0, "'radius'");
  double length = 0.0;
  for (Eigen::Index i = 1; i < nodes.rows(); ++i) length += (nodes.row(i) - nodes.row(i - 1)).norm();
  std::unique_ptr<FramedChain> chain;
  if (!p.has("spans") && inner_radius == 0.0) {
    chain = std::make_unique<FramedChain>(std::move(nodes), radius, massFromParams(p, radius, length));
  } else if (!p.has("spans")) {
    // A tube: its density from a total mass over the wall's area, ρ = m / (π (r² − r_in²) L).
    const Section wall{radius, 1.0, inner_radius};
    const double density = p.has({"density", "kg/m³"}) && !p.has({"mass", "kg"})
                               ? p.positive({"density", "kg/m³"})
                               : massFromParams(p, radius, length) / (wall.area() * length);  // (its checks and refusals)
    const std::vector<double> lengths = segmentLengths(nodes);
    chain = std::make_unique<FramedChain>(std::move(nodes), radius,
                                          std::vector<Section>(lengths.size(), {radius, density, inner_radius}));
  } else {
    if (p.has({"mass", "kg"})) p.fail("mass", "a 'density' (kg/m³) with 'spans' (each span may change it), not a total mass");
    const double density = p.positive({"density", "kg/m³"});
    const std::vector<double> lengths = segmentLengths(nodes);
    std::vector<Section> sections(lengths.size(), {radius, density, inner_radius});
    for (const Params& span : p.objects("spans")) {
      const double from = span.abscissa("from"), to = span.abscissa("to");
      if (!(to > from)) span.fail("to", "an abscissa above 'from' (" + std::to_string(from) + ")", std::to_string(to));
      const double r = span.positive({"radius", "m"}, radius), rho = span.positive({"density", "kg/m³"}, density);
      const double inner = innerRadiusFromParams(span, r, inner_radius, "the span's radius");
      span.finish();
      double arc = 0.0;
      for (std::size_t i = 0; i < lengths.size(); arc += lengths[i], ++i)
        if (const double middle = (arc + lengths[i] / 2.0) / length; middle >= from && middle <= to)
          sections[i] = {r, rho, inner};
    }
    chain = std::make_unique<FramedChain>(std::move(nodes), radius, std::move(sections));
  }
  if (p.has("angular_velocities"))
    chain->initial_angular_velocities_ =
        p.points({"angular_velocities", "rad/s"}, chain->segmentCount(), chain->segmentCount(), "framed_chain.hpp: one per segment");
  return chain;
}

void FramedChain::solveMass(PointsRef B) const {
  for (int i = 0; i < pointCount(); ++i) B.row(i) /= masses_[i];
}

void FramedChain::multiplyMass(ConstPointsRef x, PointsRef out) const {
  for (int i = 0; i < pointCount(); ++i) out.row(i) = masses_[i] * x.row(i);
}

void FramedChain::addMassMatrix(double factor, JacobianAccumulator& out) const {
  for (int i = 0; i < pointCount(); ++i) out.addIsotropic(offset() + i, offset() + i, factor * masses_[i]);
}

void FramedChain::addGravity(const Vec3& g, PointsRef B) const {
  for (int i = 0; i < pointCount(); ++i) B.row(i) += masses_[i] * g.transpose();
}

double FramedChain::gravityPotential(const Vec3& g, ConstPointsRef q) const {
  double v = 0.0;
  for (int i = 0; i < pointCount(); ++i) v -= masses_[i] * g.dot(q.row(i).transpose());
  return v;
}

void FramedChain::initialInternalState(Eigen::Ref<VecX> q, Eigen::Ref<VecX> v) const {
  for (int i = 0; i < segmentCount(); ++i) store(initial_frames_[i], q, i);
  if (initial_angular_velocities_.rows() == 0)
    v.setZero();
  else
    for (int i = 0; i < segmentCount(); ++i) v.segment<3>(3 * i) = initial_angular_velocities_.row(i).transpose();
}

void FramedChain::integrateInternal(Eigen::Ref<const VecX> q0, Eigen::Ref<const VecX> w, Eigen::Ref<VecX> q1) const {
  // R ← R exp(w_i) per segment, renormalized: the product of two unit quaternions is unit to a
  // few roundings, |q|² = 1 + δ with δ ~ 1e-16, so one Newton step for 1/√|q|², q (3 − |q|²)/2,
  // restores it to O(δ²) — round-off — without a square root.
  for (int i = 0; i < segmentCount(); ++i) {
    const Eigen::Quaterniond r = quaternionAt(q0, i) * geometry::rotationExp(w.segment<3>(3 * i));
    store(Eigen::Quaterniond(r.coeffs() * (0.5 * (3.0 - r.squaredNorm()))), q1, i);
  }
}

void FramedChain::differenceInternal(Eigen::Ref<const VecX> q1, Eigen::Ref<const VecX> q0, Eigen::Ref<VecX> w) const {
  for (int i = 0; i < segmentCount(); ++i)
    w.segment<3>(3 * i) = geometry::rotationLog(quaternionAt(q0, i).conjugate() * quaternionAt(q1, i));
}

void FramedChain::addInternalForce(const SceneState& s, Eigen::Ref<VecX> B) const {
  // Euler's equations in the body frame: J ω̇ = τ − ω × J ω.
  const auto omega = internalVelocities(s.v);
  for (int i = 0; i < segmentCount(); ++i) {
    const Vec3 w = omega.segment<3>(3 * i);
    B.segment<3>(3 * i) -= w.cross(inertia_[i].cwiseProduct(w));
  }
}

void FramedChain::solveInternalMass(Eigen::Ref<VecX> B) const {
  for (int i = 0; i < segmentCount(); ++i) B.segment<3>(3 * i) = B.segment<3>(3 * i).cwiseQuotient(inertia_[i]);
}

void FramedChain::addInternalMassMatrix(double factor, JacobianAccumulator& out) const {
  for (int i = 0; i < segmentCount(); ++i)
    out.addBlock(internalGroup(i), internalGroup(i), Eigen::Matrix3d((factor * inertia_[i]).asDiagonal()));
}

void FramedChain::multiplyInternalMass(Eigen::Ref<const VecX> x, Eigen::Ref<VecX> out) const {
  for (int i = 0; i < segmentCount(); ++i) out.segment<3>(3 * i) = inertia_[i].cwiseProduct(x.segment<3>(3 * i));
}

SparseMatrix FramedChain::refine(const std::vector<double>&) {
  throw SceneError(origin(), "a body whose point count may change (a DynamicSpline) to insert points into",
                   describe() + ", whose segments carry frames");
}

SparseMatrix FramedChain::coarsen(double, ConstPointsRef, double) {
  throw SceneError(origin(), "a body whose point count may change (a DynamicSpline) to remove points from",
                   describe() + ", whose segments carry frames");
}

SparseMatrix FramedChain::cut(double) {
  throw SceneError(origin(), "a body whose point count may change (a DynamicSpline) to cut",
                   describe() + ", whose segments carry frames");
}

int FramedChain::segmentAt(double s) const {
  BasisRow row;
  basis_->evaluate(s, row);  // degree 1: the support is the segment's two nodes
  return std::clamp(row.first, 0, segmentCount() - 1);
}

double FramedChain::radiusAt(double s) const {
  if (!radius_varies_) return radius_;
  return sectionField(s, &Section::radius, true);
}

double FramedChain::innerRadiusAt(double s) const {
  if (!inner_radius_varies_) return sections_.empty() ? 0.0 : sections_.front().inner_radius;
  return sectionField(s, &Section::inner_radius, false);
}

double FramedChain::sectionField(double s, double Section::*field, bool larger) const {
  // node_abscissas_[i] <= s < node_abscissas_[i + 1] on segment i. At an interior node both
  // segments meet: "at" within a few ulps (abscissas <= 1), since an abscissa placed at a node by
  // another sum (a contact sphere's, from its arc-length table) may differ from it in the last bit.
  constexpr double kAtNode = 8.0 * std::numeric_limits<double>::epsilon();
  const int segments = segmentCount();
  const auto above = std::upper_bound(node_abscissas_.begin(), node_abscissas_.end(), s);
  const int segment = std::clamp(static_cast<int>(above - node_abscissas_.begin()) - 1, 0, segments - 1);
  const auto pick = [larger](double a, double b) { return larger ? std::max(a, b) : std::min(a, b); };
  double value = sections_[segment].*field;
  if (segment > 0 && std::abs(s - node_abscissas_[segment]) <= kAtNode) value = pick(value, sections_[segment - 1].*field);
  if (segment + 1 < segments && std::abs(s - node_abscissas_[segment + 1]) <= kAtNode)
    value = pick(value, sections_[segment + 1].*field);
  return value;
}

void FramedChain::addTorque(const SceneState& st, double s, const Vec3& torque, VecX& B) const {
  const int segment = segmentAt(s);
  internalVelocities(B).segment<3>(3 * segment) += orientation(st.q, segment).conjugate() * torque;
}

Eigen::Quaterniond FramedChain::orientation(const VecX& q, int segment) const {
  return quaternionAt(internalPositions(q), segment);
}

}  // namespace filum::mechanics
