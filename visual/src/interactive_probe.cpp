#include "filum/visual/interactive_probe.hpp"

#include <cmath>
#include <limits>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/closest_point.hpp"
#include "filum/core/curve_body.hpp"
#include "filum/visual/sphere_mesh.hpp"

namespace filum::visual {

namespace {

constexpr double kPushOmegaDt = 0.3;  // ω dt of the push penalty on one sample
constexpr double kGrabOmegaDt = 0.5;  // ω dt of the grab spring

}  // namespace

bool startGrab(ProbeState& probe, const Scene& scene, double capture) {
  probe.grabbing = false;
  probe.grab_body = nullptr;
  double best = capture;
  for (const MechanicalState* body : scene.bodies()) {
    const auto* spline = body->curve();
    if (!spline) continue;
    const geometry::ClosestPoint c = geometry::closestPoint(spline->basis(), body->block(scene.state().q), probe.position);
    if (c.distance <= best) {
      best = c.distance;
      probe.grabbing = true;
      probe.grab_body = body;
      probe.grab_abscissa = c.s;
    }
  }
  return probe.grabbing;
}

ProbeForceField::ProbeForceField(std::shared_ptr<const ProbeState> probe, int samples)
    : probe_(std::move(probe)), samples_(samples) {}

void ProbeForceField::init(const Scene& scene) {
  const auto* spline = body().curve();
  if (!spline) throw SceneError(origin(), "the mouse probe acts on curve bodies (e.g. DynamicSpline), not on " + body().describe());
  dt_ = scene.settings().dt;
  thread_radius_ = spline->radius();
  const int n = spline->pointCount();
  const int m = samples_ > 0 ? samples_ : std::max(8, 4 * n);
  std::vector<double> s(m);
  for (int k = 0; k < m; ++k) s[k] = static_cast<double>(k) / (m - 1);
  mapping_ = std::make_unique<SplineAxisMapping>(spline->basis(), s);
  x_.resize(m, 3);
  f_.resize(m, 3);
  unit_load_.resize(n, 3);
  response_.resize(n, 3);
  mass_abscissa_ = std::numeric_limits<double>::quiet_NaN();  // no cached mass (NaN equals nothing)
  sample_mass_ = effectiveMass(0.5);
}

double ProbeForceField::effectiveMass(double s) const {
  // bᵀ M⁻¹ b with one banded solve (M is the same on x, y and z: use the first column), in the
  // workspace sized by init, and kept for the last abscissa asked (the grab's, every call).
  if (s == mass_abscissa_) return mass_at_abscissa_;
  const auto& spline = *body().curve();
  geometry::BasisRow row;
  spline.basis().evaluate(s, row);
  unit_load_.setZero();
  for (int j = 0; j < row.count; ++j) unit_load_(row.first + j, 0) = row.value[j];
  response_ = unit_load_;
  spline.solveMass(response_);
  mass_abscissa_ = s;
  mass_at_abscissa_ = 1.0 / unit_load_.col(0).dot(response_.col(0));
  return mass_at_abscissa_;
}

double ProbeForceField::pushStiffness() const {
  return std::min(probe_->push_stiffness, kPushOmegaDt * kPushOmegaDt * sample_mass_ / (dt_ * dt_));
}

double ProbeForceField::grabStiffness() const {
  const double m = effectiveMass(probe_->grab_abscissa);
  return std::min(probe_->grab_stiffness, kGrabOmegaDt * kGrabOmegaDt * m / (dt_ * dt_));
}

double ProbeForceField::grabDamping() const {
  return 2.0 * std::sqrt(grabStiffness() * effectiveMass(probe_->grab_abscissa));
}

void ProbeForceField::addForce(const SceneState& s, VecX& B) const {
  if (!probe_->touching && !grabbing()) return;
  const ConstPointsMap q = body().block(s.q);
  PointsMap Q = body().block(B);
  if (probe_->touching && !grabbing()) {
    // Push: penalty on the samples inside the sphere, mapped up by Wᵀ.
    const double k = pushStiffness(), R = probe_->radius + thread_radius_;
    mapping_->apply(q, x_);
    f_.setZero();
    bool any = false;
    for (Eigen::Index i = 0; i < x_.rows(); ++i) {
      const Vec3 d = x_.row(i).transpose() - probe_->position;
      const double dist = d.norm();
      if (dist >= R || dist == 0.0) continue;
      f_.row(i) = (k * (R - dist) / dist * d).transpose();
      any = true;
    }
    if (any) mapping_->applyJT(q, f_, Q);
  }
  if (grabbing()) {
    // Grab: spring–damper between the probe and P(s*).
    const auto& spline = *body().curve();
    geometry::BasisRow row;
    spline.basis().evaluate(probe_->grab_abscissa, row);
    const ConstPointsMap v = body().block(s.v);
    Vec3 P = Vec3::Zero(), V = Vec3::Zero();
    for (int j = 0; j < row.count; ++j) {
      P += row.value[j] * q.row(row.first + j).transpose();
      V += row.value[j] * v.row(row.first + j).transpose();
    }
    const Vec3 F = grabStiffness() * (probe_->position - P) - grabDamping() * V;
    for (int j = 0; j < row.count; ++j) Q.row(row.first + j) += row.value[j] * F.transpose();
  }
}

double ProbeForceField::potentialEnergy(const SceneState& s) const {
  if (!probe_->touching && !grabbing()) return 0.0;
  const ConstPointsMap q = body().block(s.q);
  double energy = 0.0;
  if (grabbing()) {
    const auto& spline = *body().curve();
    geometry::BasisRow row;
    spline.basis().evaluate(probe_->grab_abscissa, row);
    Vec3 P = Vec3::Zero();
    for (int j = 0; j < row.count; ++j) P += row.value[j] * q.row(row.first + j).transpose();
    energy += 0.5 * grabStiffness() * (probe_->position - P).squaredNorm();
  } else {
    const double k = pushStiffness(), R = probe_->radius + thread_radius_;
    mapping_->apply(q, x_);
    for (Eigen::Index i = 0; i < x_.rows(); ++i) {
      const double dist = (x_.row(i).transpose() - probe_->position).norm();
      if (dist < R) energy += 0.5 * k * (R - dist) * (R - dist);
    }
  }
  return energy;
}

void ProbeForceField::addJacobian(const SceneState& s, double k_factor, double d_factor,
                                  JacobianAccumulator& out) const {
  if (!probe_->touching && !grabbing()) return;
  const int offset = body().offset();
  const auto emit = [&](int i, int j, const Eigen::Matrix3d& block) { out.addBlock(offset + i, offset + j, block); };
  const auto& spline = *body().curve();
  geometry::BasisRow row;
  if (grabbing()) {
    spline.basis().evaluate(probe_->grab_abscissa, row);
    const double k = grabStiffness(), c = grabDamping();
    for (int a = 0; a < row.count; ++a)
      for (int b = 0; b < row.count; ++b)
        emit(row.first + a, row.first + b,
             (-(k_factor * k + d_factor * c) * row.value[a] * row.value[b]) * Eigen::Matrix3d::Identity());
    return;
  }
  const ConstPointsMap q = body().block(s.q);
  const double k = pushStiffness(), R = probe_->radius + thread_radius_;
  mapping_->apply(q, x_);
  const std::vector<double>& abscissas = mapping_->abscissas();
  for (Eigen::Index i = 0; i < x_.rows(); ++i) {
    const Vec3 d = x_.row(i).transpose() - probe_->position;
    const double dist = d.norm();
    if (dist >= R || dist == 0.0) continue;
    const Vec3 n = d / dist;
    const Eigen::Matrix3d nn = n * n.transpose();
    const Eigen::Matrix3d G = k * (-nn + (R - dist) / dist * (Eigen::Matrix3d::Identity() - nn));
    spline.basis().evaluate(abscissas[i], row);
    for (int a = 0; a < row.count; ++a)
      for (int b = 0; b < row.count; ++b) emit(row.first + a, row.first + b, (k_factor * row.value[a] * row.value[b]) * G);
  }
}

ProbeVisual::ProbeVisual(std::shared_ptr<const ProbeState> probe) : probe_(std::move(probe)), unit_(unitSphere(12)) {
  setName("probe");
}

void ProbeVisual::update(const SceneState&) {
  mesh_ = TriangleMesh{};
  mesh_.vertices.resize(0, 3);
  mesh_.normals.resize(0, 3);
  mesh_.triangles.resize(0, 3);
  if (!probe_->touching && !probe_->grabbing) return;
  setMaterial(Material{probe_->grabbing ? Vec3(0.2, 0.75, 0.3) : Vec3(0.9, 0.2, 0.15), 0.6});
  appendSphere(unit_, probe_->position, probe_->radius, mesh_);
}

}  // namespace filum::visual
