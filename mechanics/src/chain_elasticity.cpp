#include "filum/mechanics/chain_elasticity.hpp"

#include <numbers>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/framed_chain.hpp"

namespace filum::mechanics {

std::unique_ptr<ChainElasticity> ChainElasticity::fromParams(const Params& p) {
  const double nu = p.nonNegative("poisson_ratio", 0.5);
  if (nu > 0.5) p.fail("poisson_ratio", "a Poisson ratio in [0, 0.5]", std::to_string(nu));
  return std::make_unique<ChainElasticity>(p.positive("youngs_modulus"), nu);
}

void ChainElasticity::init(const Scene&) {
  chain_ = dynamic_cast<const FramedChain*>(&body());
  if (!chain_) throw SceneError(origin(), "a FramedChain body for " + describe(), body().describe());
  const double r = chain_->radius(), area = std::numbers::pi * r * r, second = area * r * r / 4.0;
  const double shear_modulus = youngs_modulus_ / (2.0 * (1.0 + poisson_ratio_));
  axial_ = youngs_modulus_ * area;
  shear_ = 0.9 * shear_modulus * area;  // κ = 0.9: a disc's shear coefficient (about 0.89–0.9)
  bending_ = Vec3(youngs_modulus_ * second, youngs_modulus_ * second, shear_modulus * 2.0 * second);
}

double ChainElasticity::segment(const SceneState& s, int i, VecX* forces) const {
  const FramedChain& chain = *chain_;
  const ConstPointsMap x = chain.block(s.q);
  const double l = chain.restLength(i);
  const Vec3 e = (x.row(i + 1) - x.row(i)).transpose();
  const double length = e.norm();
  const Vec3 t = e / length;
  const Eigen::Quaterniond R = chain.orientation(s.q, i);
  const Vec3 d3 = R * Vec3::UnitZ();
  const double energy = 0.5 * axial_ / l * (length - l) * (length - l) + 0.5 * shear_ * l * (d3 - t).squaredNorm();
  if (!forces) return energy;

  // ∂E/∂d3 = κGA l (d3 − t) = g, ∂E/∂t = −g; through t = e/|e|, ∂t/∂e = (I − t tᵀ)/|e|.
  const Vec3 g = shear_ * l * (d3 - t);
  const Vec3 dE_de = (axial_ / l * (length - l)) * t - (g - t * t.dot(g)) / length;
  VecX& B = *forces;
  const int a = chain.offset() + i, b = a + 1;
  B.segment<3>(3 * a) += dE_de;  // e = x_b − x_a: Q_a = +∂E/∂e, Q_b = −∂E/∂e
  B.segment<3>(3 * b) -= dE_de;
  chain.internalVelocities(B).segment<3>(3 * i) -= Vec3::UnitZ().cross(R.conjugate() * g);
  return energy;
}

double ChainElasticity::joint(const SceneState& s, int j, VecX* forces) const {
  const FramedChain& chain = *chain_;
  const double voronoi = 0.5 * (chain.restLength(j - 1) + chain.restLength(j));
  const Eigen::Quaterniond Ra = chain.orientation(s.q, j - 1), Rb = chain.orientation(s.q, j);
  const Vec3 phi = geometry::rotationLog(Ra.conjugate() * Rb);
  const Vec3 moment = bending_.cwiseProduct(phi) / voronoi;  // B φ / ℓ
  const double energy = 0.5 * phi.dot(moment);
  if (!forces) return energy;
  auto torques = chain.internalVelocities(*forces);
  torques.segment<3>(3 * (j - 1)) += geometry::leftJacobianInverse(phi).transpose() * moment;
  torques.segment<3>(3 * j) -= geometry::rightJacobianInverse(phi).transpose() * moment;
  return energy;
}

void ChainElasticity::addForce(const SceneState& s, VecX& B) const {
  for (int i = 0; i < chain_->segmentCount(); ++i) segment(s, i, &B);
  for (int j = 1; j < chain_->segmentCount(); ++j) joint(s, j, &B);
}

double ChainElasticity::potentialEnergy(const SceneState& s) const {
  double energy = 0.0;
  for (int i = 0; i < chain_->segmentCount(); ++i) energy += segment(s, i, nullptr);
  for (int j = 1; j < chain_->segmentCount(); ++j) energy += joint(s, j, nullptr);
  return energy;
}

}  // namespace filum::mechanics
