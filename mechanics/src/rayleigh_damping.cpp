#include "filum/mechanics/rayleigh_damping.hpp"

#include "filum/core/scene_error.hpp"

#include <algorithm>

#include "filum/core/scene.hpp"
#include "filum/mechanics/stiffness_derivative.hpp"
#include "filum/mechanics/viscous_damping.hpp"

namespace filum::mechanics {

std::unique_ptr<RayleighDamping> RayleighDamping::fromParams(const Params& p) {
  const std::string update = p.string("stiffness_update", "per_state");
  if (update != "per_state" && update != "per_step")
    p.fail("stiffness_update", "\"per_state\" or \"per_step\"", "\"" + update + "\"");
  return std::make_unique<RayleighDamping>(p.nonNegative({"stiffness_coefficient", "s"}, 0.0), update == "per_step");
}

void RayleighDamping::init(const Scene& scene) {
  // Its stiffness cache spans the body's points only: a rod's frames (internal DOFs) have no
  // place in it.
  if (body().internalVelocityCount() > 0)
    throw SceneError(origin(), "a body without internal DOFs for " + describe() + " (use ViscousDamping on a rod)",
                     body().describe() + ", whose frames are internal DOFs");
  scene_ = &scene;
  resolved_ = false;
  stiffness_valid_ = false;
}

const std::vector<const ForceField*>& RayleighDamping::elasticFields() const {
  if (!resolved_) {
    elastic_.clear();
    for (const ForceField* field : scene_->forceFields()) {
      if (field == this || !field->bound() || &field->body() != &body()) continue;
      if (dynamic_cast<const RayleighDamping*>(field) || dynamic_cast<const ViscousDamping*>(field)) continue;
      if (field->hasJacobian()) elastic_.push_back(field);
    }
    resolved_ = true;
  }
  return elastic_;
}

const BlockBandMatrix& RayleighDamping::stiffness(const SceneState& s) const {
  // The key is the body's positions and velocities (a spring's ∂Q/∂q has dashpot terms in q̇).
  // Lagged (per_step): the key is the time alone.
  const Eigen::Index offset = 3 * body().offset(), size = 3 * body().pointCount();
  const bool stale = per_step_ ? !stiffness_valid_ || stiffness_time_ != s.time
                               : !stiffness_valid_ || stiffness_key_.head(size) != s.q.segment(offset, size) ||
                                     stiffness_key_.tail(size) != s.v.segment(offset, size);
  if (stale) {
    if (stiffness_.firstPoint() != body().offset() || stiffness_.points() != body().pointCount())
      stiffness_.resize(body().offset(), body().pointCount(), std::max(0, body().couplingRange()));
    // K over the band the body declares; a field whose Jacobian reaches further (a global
    // energy's rank-one term) widens it once, and K is filled again.
    for (int pass = 0; pass < 2; ++pass) {
      stiffness_.setZero();
      for (const ForceField* field : elasticFields()) field->addJacobian(s, 1.0, 0.0, stiffness_);
      if (stiffness_.misfits() == 0 || stiffness_.neededRange() <= stiffness_.range()) break;
      stiffness_.resize(body().offset(), body().pointCount(), stiffness_.neededRange());
    }
    if (!per_step_) {  // lagged: the time is the whole key
      stiffness_key_.resize(2 * size);
      stiffness_key_ << s.q.segment(offset, size), s.v.segment(offset, size);
    }
    stiffness_valid_ = true;
    stiffness_time_ = s.time;
  }
  return stiffness_;
}

void RayleighDamping::addForce(const SceneState& s, VecX& B) const {
  // Q = β K(q) q̇, K from the elastic fields' analytic Jacobians (k_factor = 1, no damping part).
  const Eigen::Index offset = 3 * body().offset(), size = 3 * body().pointCount();
  stiffness(s).multiplyAdd(s.v.segment(offset, size), beta_, B.segment(offset, size));
}

void RayleighDamping::addJacobian(const SceneState& s, double k_factor, double d_factor,
                                  JacobianAccumulator& out) const {
  if (beta_ == 0.0) return;
  // ∂Q/∂q̇ = β K(q).
  if (d_factor != 0.0) stiffness(s).addSymmetrizedTo(d_factor * beta_, out);
  // ∂Q/∂q = β ∂(K(q) q̇)/∂q, from the fields that can differentiate their stiffness (0 when K
  // is lagged).
  if (k_factor != 0.0 && !per_step_)
    for (const ForceField* field : elasticFields())
      if (const auto* derivative = dynamic_cast<const StiffnessDerivative*>(field))
        derivative->addStiffnessDerivative(s, s.v, k_factor * beta_, out);
}

}  // namespace filum::mechanics
