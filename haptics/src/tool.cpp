#include "filum/haptics/tool.hpp"

#include <algorithm>
#include <cmath>

#include "filum/core/curve_body.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/closest_point.hpp"
#include "filum/geometry/spline_curve.hpp"

namespace filum::haptics {

namespace {

constexpr double kPushOmegaDt = 0.3;   // ω dt of the push penalty on one sample (explicit steps)
constexpr double kGraspOmegaDt = 0.5;  // ω dt of the grasp spring (explicit steps)

}  // namespace

bool startGrasp(ToolState& tool, const Scene& scene, double capture) {
  release(tool);
  double best = capture;
  for (const MechanicalState* body : scene.bodies()) {
    const CurveBody* curve = body->curve();
    if (!curve) continue;
    const geometry::ClosestPoint c = geometry::closestPoint(curve->basis(), body->block(scene.state().q), tool.position);
    if (c.distance <= best) {
      best = c.distance;
      grasp(tool, *curve, c.s);
    }
  }
  return tool.grasping;
}

void grasp(ToolState& tool, const CurveBody& body, double abscissa) {
  tool.grasping = true;
  tool.grasp.attach(body, abscissa);
}

void release(ToolState& tool) {
  tool.grasping = false;
  tool.grasp.detach();
}

ToolForceField::ToolForceField(std::shared_ptr<const ToolState> tool, int samples)
    : tool_(std::move(tool)), samples_(samples) {}

void ToolForceField::init(const Scene& scene) {
  const CurveBody* curve = body().curve();
  if (!curve)
    throw SceneError(origin(), "the interaction tool acts on curve bodies (e.g. DynamicSpline), not on " + body().describe());
  dt_ = scene.settings().dt;
  explicit_step_ = !scene.integrator().needsJacobians();
  const int n = curve->pointCount();
  const int m = samples_ > 0 ? samples_ : std::max(8, 4 * n);
  push_points_.resize(m);
  sample_radii_.resize(m);
  for (int k = 0; k < m; ++k) {
    const double s = static_cast<double>(k) / (m - 1);
    push_points_[k].attach(*curve, s);
    sample_radii_[k] = curve->radiusAt(s);  // the thread's section there (a rod's spans)
  }
  unit_load_.resize(n, 3);
  response_.resize(n, 3);
  mass_abscissa_ = std::numeric_limits<double>::quiet_NaN();  // nothing cached (NaN equals nothing)
  sample_mass_ = effectiveMass(0.5);
}

double ToolForceField::effectiveMass(double s) const {
  // bᵀ M⁻¹ b with one banded solve (M is the same on x, y and z: use the first column), in the
  // workspace sized by init, and kept for the last abscissa asked (the grasp's, every call).
  if (s == mass_abscissa_) return mass_at_abscissa_;
  geometry::BasisRow row;
  body().curve()->basis().evaluate(s, row);
  unit_load_.setZero();
  for (int j = 0; j < row.count; ++j) unit_load_(row.first + j, 0) = row.value[j];
  response_ = unit_load_;
  body().solveMass(response_);
  mass_abscissa_ = s;
  mass_at_abscissa_ = 1.0 / unit_load_.col(0).dot(response_.col(0));
  return mass_at_abscissa_;
}

double ToolForceField::gain(double requested, double cap) const {
  if (std::isinf(requested)) return cap;
  return explicit_step_ ? std::min(requested, cap) : requested;
}

double ToolForceField::pushStiffness() const {
  return gain(tool_->push_stiffness, kPushOmegaDt * kPushOmegaDt * sample_mass_ / (dt_ * dt_));
}

double ToolForceField::graspStiffness() const {
  const double m = effectiveMass(tool_->grasp.abscissa());
  return gain(tool_->grasp_stiffness, kGraspOmegaDt * kGraspOmegaDt * m / (dt_ * dt_));
}

double ToolForceField::graspDamping() const {
  if (tool_->grasp_damping >= 0.0) return tool_->grasp_damping;
  return 2.0 * std::sqrt(graspStiffness() * effectiveMass(tool_->grasp.abscissa()));
}

void ToolForceField::graspPoint(const SceneState& s, Vec3& P, Vec3& V) const {
  P = tool_->grasp.map(s.q);
  V = tool_->grasp.map(s.v);
}

Eigen::Matrix3d ToolForceField::Overlap::jacobian() const {
  const Eigen::Matrix3d nn = normal * normal.transpose();
  return stiffness * (-nn + depth() / distance * (Eigen::Matrix3d::Identity() - nn));
}

template <typename Visit>
void ToolForceField::forEachOverlap(const SceneState& s, Visit visit) const {
  const double k = pushStiffness();
  const Vec3 X = toolPosition(*tool_, s.time);
  for (std::size_t i = 0; i < push_points_.size(); ++i) {
    const BodyPoint& point = push_points_[i];
    const double R = tool_->radius + sample_radii_[i];
    const Vec3 d = point.map(s.q) - X;
    const double distance = d.norm();
    if (distance >= R || distance == 0.0) continue;
    visit(Overlap{point, distance, R, k, d / distance});
  }
}

void ToolForceField::addForce(const SceneState& s, VecX& B) const {
  if (!pushing() && !grasping()) return;
  if (grasping()) {
    Vec3 P, V;
    graspPoint(s, P, V);
    const Vec3 F = graspStiffness() * (toolPosition(*tool_, s.time) - P) + graspDamping() * (tool_->velocity - V);
    tool_->grasp.addForce(F, B);
    return;
  }
  forEachOverlap(s, [&](const Overlap& o) { o.point.addForce(o.force(), B); });
}

double ToolForceField::potentialEnergy(const SceneState& s) const {
  if (!pushing() && !grasping()) return 0.0;
  if (grasping()) {
    Vec3 P, V;
    graspPoint(s, P, V);
    return 0.5 * graspStiffness() * (toolPosition(*tool_, s.time) - P).squaredNorm();
  }
  double energy = 0.0;  // ½ k (R − d)² per sample inside
  forEachOverlap(s, [&](const Overlap& o) { energy += 0.5 * o.stiffness * o.depth() * o.depth(); });
  return energy;
}

void ToolForceField::addJacobian(const SceneState& s, double k_factor, double d_factor, JacobianAccumulator& out) const {
  if (!pushing() && !grasping()) return;
  // Jᵀ (∂F/∂x) J over the mapping row of the point (the grasp's, or each pushed sample's).
  if (grasping()) {
    const double k = graspStiffness(), c = graspDamping();
    const BodyPoint& grasp = tool_->grasp;
    grasp.forEachWeight([&](int a, double wa) {
      grasp.forEachWeight([&](int b, double wb) {
        out.addBlock(a, b, (-(k_factor * k + d_factor * c) * wa * wb) * Eigen::Matrix3d::Identity());
      });
    });
    return;
  }
  forEachOverlap(s, [&](const Overlap& o) {
    const Eigen::Matrix3d G = o.jacobian();
    o.point.forEachWeight([&](int a, double wa) {
      o.point.forEachWeight([&](int b, double wb) { out.addBlock(a, b, (k_factor * wa * wb) * G); });
    });
  });
}

void ToolForceField::addReaction(const SceneState& s, ToolReaction& out) const {
  if (grasping()) {
    // F_tool = −F = k (P − X) + c (Ṗ − Ẋ): ∂/∂X = −k I, ∂/∂Ẋ = −c I.
    Vec3 P, V;
    graspPoint(s, P, V);
    const double k = graspStiffness(), c = graspDamping();
    out.force += k * (P - toolPosition(*tool_, s.time)) + c * (V - tool_->velocity);
    out.stiffness -= k * Eigen::Matrix3d::Identity();
    out.damping -= c * Eigen::Matrix3d::Identity();
    return;
  }
  if (!pushing()) return;
  // F_tool = −Σ F_k, and ∂F_k/∂X = −∂F_k/∂x_k = −G_k: ∂F_tool/∂X = Σ G_k.
  forEachOverlap(s, [&](const Overlap& o) {
    out.force -= o.force();
    out.stiffness += o.jacobian();
  });
}

}  // namespace filum::haptics
