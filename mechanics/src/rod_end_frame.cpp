#include "filum/mechanics/rod_end_frame.hpp"

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/chain_elasticity.hpp"
#include "filum/mechanics/framed_chain.hpp"

namespace filum::mechanics {

std::unique_ptr<RodEndFrame> RodEndFrame::fromParams(const Params& p) {
  const std::string end = p.string("end", "start");
  if (end != "start" && end != "end") p.fail("end", "\"start\" or \"end\"", "\"" + end + "\"");
  std::optional<Vec3> direction;
  if (p.has("direction")) {
    direction = p.vec3("direction");
    if (!(direction->norm() > 0.0)) p.fail("direction", "a non-zero direction");
    direction->normalize();
  }
  return std::make_unique<RodEndFrame>(end == "start" ? End::kStart : End::kFinish, direction, p.number("roll", 0.0));
}

void RodEndFrame::init(const Scene& scene) {
  chain_ = dynamic_cast<const FramedChain*>(&body());
  if (!chain_) throw SceneError(origin(), "a FramedChain body for " + describe(), body().describe());
  const ChainElasticity* elasticity = nullptr;
  for (const ForceField* field : scene.forceFields())
    if (const auto* candidate = dynamic_cast<const ChainElasticity*>(field);
        candidate && candidate->bound() && &candidate->body() == &body())
      elasticity = candidate;
  if (!elasticity)
    throw SceneError(origin(),
                     "a ChainElasticity on " + body().describe() +
                         " listed before this component (the rod's bending and twist stiffness)",
                     "none");
  const int segment = end_ == End::kStart ? 0 : chain_->segmentCount() - 1;
  stiffness_ = elasticity->bendingTwistingStiffness() / (0.5 * chain_->restLength(segment));
  const Eigen::Quaterniond initial = chain_->initialFrame(segment);
  const Vec3 tangent = initial * Vec3::UnitZ(), d = direction_.value_or(tangent);
  held_ = (Eigen::Quaterniond(Eigen::AngleAxisd(roll_, d)) * Eigen::Quaterniond::FromTwoVectors(tangent, d) * initial)
              .normalized();
}

double RodEndFrame::term(const SceneState& s, VecX* forces) const {
  const bool start = end_ == End::kStart;
  const int segment = start ? 0 : chain_->segmentCount() - 1;
  const Eigen::Quaterniond R = chain_->orientation(s.q, segment);
  const Vec3 phi = geometry::rotationLog(start ? held_.conjugate() * R : R.conjugate() * held_);
  const Vec3 moment = stiffness_.cwiseProduct(phi);  // B φ / ℓ
  if (forces) {
    auto torque = chain_->internalVelocities(*forces).segment<3>(3 * segment);
    if (start)
      torque -= geometry::rightJacobianInverse(phi).transpose() * moment;
    else
      torque += geometry::leftJacobianInverse(phi).transpose() * moment;
  }
  return 0.5 * phi.dot(moment);
}

void RodEndFrame::addForce(const SceneState& s, VecX& B) const { term(s, &B); }

double RodEndFrame::potentialEnergy(const SceneState& s) const { return term(s, nullptr); }

}  // namespace filum::mechanics
