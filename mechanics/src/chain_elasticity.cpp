#include "filum/mechanics/chain_elasticity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/rotation_vector.hpp"
#include "filum/mechanics/framed_chain.hpp"

namespace filum::mechanics {

namespace {

/// E, ν and the rest curvature of `p` over `base` (what it leaves out stays as in base).
ChainElasticity::Span spanFromParams(const Params& p, ChainElasticity::Span base) {
  base.youngs_modulus = p.has("youngs_modulus") || base.youngs_modulus == 0.0 ? p.positive({"youngs_modulus", "Pa"})
                                                                               : base.youngs_modulus;
  base.poisson_ratio = p.nonNegative({"poisson_ratio", "1"}, base.poisson_ratio);
  if (base.poisson_ratio > 0.5)
    p.fail("poisson_ratio", "a Poisson ratio in [0, 0.5]", std::to_string(base.poisson_ratio));
  if (p.has("rest_curvature")) {
    const nlohmann::json& k = p.raw({"rest_curvature", "rad/m"});
    if (!k.is_array() || k.size() != 2 || !k[0].is_number() || !k[1].is_number() ||
        !std::isfinite(k[0].get<double>()) || !std::isfinite(k[1].get<double>()))
      p.fail("rest_curvature", "[κ1, κ2]: two finite numbers (rad/m, about d1 and d2)", k.dump());
    base.rest_curvature.head<2>() = Eigen::Vector2d(k[0].get<double>(), k[1].get<double>());
  }
  base.rest_curvature.z() = p.number({"rest_twist", "rad/m"}, base.rest_curvature.z());
  return base;
}

/// Timoshenko's shear coefficient of a circular tube, lumen over outer radius m = r_in / r
/// (G. R. Cowper, "The shear coefficient in Timoshenko's beam theory", J. Appl. Mech. 33 (1966)
/// 335, Table 1, hollow circle):
///   κ = 6 (1 + ν)(1 + m²)² / ((7 + 6ν)(1 + m²)² + (20 + 12ν) m²);
/// a disc (m = 0) has 6 (1 + ν)/(7 + 6ν): 0.9 at ν = ½, 0.886 at ν = 0.3; a thin wall tends to
/// 2 (1 + ν)/(4 + 3ν).
double shearCoefficient(double nu, double m) {
  const double a = (1.0 + m * m) * (1.0 + m * m);
  return 6.0 * (1.0 + nu) * a / ((7.0 + 6.0 * nu) * a + (20.0 + 12.0 * nu) * m * m);
}

}  // namespace

std::unique_ptr<ChainElasticity> ChainElasticity::fromParams(const Params& p) {
  std::vector<Span> spans{spanFromParams(p, Span{})};
  const std::string rest = p.string("rest_shape", "straight");
  if (rest != "straight" && rest != "initial") p.fail("rest_shape", "\"straight\" or \"initial\"", "\"" + rest + "\"");
  const bool initial = rest == "initial";
  if (initial && (p.has("rest_curvature") || p.has("rest_twist")))
    p.fail("rest_shape", "either a rest curvature or \"rest_shape\": \"initial\", not both");
  if (p.has("spans"))
    for (const Params& span : p.objects("spans")) {
      Span next = spanFromParams(span, spans.front());
      next.from = span.abscissa("from");
      next.to = span.abscissa("to");
      if (!(next.to > next.from))
        span.fail("to", "an abscissa above 'from' (" + std::to_string(next.from) + ")", std::to_string(next.to));
      if (initial && (span.has("rest_curvature") || span.has("rest_twist")))
        span.fail("rest_curvature", "no rest curvature with \"rest_shape\": \"initial\"");
      span.finish();
      spans.push_back(next);
    }
  return std::make_unique<ChainElasticity>(std::move(spans), initial);
}

const ChainElasticity::Span& ChainElasticity::spanAt(double s) const {
  for (auto span = spans_.rbegin(); span != spans_.rend(); ++span)
    if (s >= span->from && s <= span->to) return *span;
  return spans_.front();
}

Vec3 ChainElasticity::restTurn(double a, double b) const {
  // κ̄ is constant between span ends: split [a, b] there, each piece's κ̄ at its middle.
  std::vector<double> cuts{a, b};
  for (const Span& span : spans_)
    for (const double end : {span.from * length_, span.to * length_})
      if (end > a && end < b) cuts.push_back(end);
  std::sort(cuts.begin(), cuts.end());
  Vec3 turn = Vec3::Zero();
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k)
    turn += (cuts[k + 1] - cuts[k]) * spanAt(0.5 * (cuts[k] + cuts[k + 1]) / length_).rest_curvature;
  return turn;
}

void ChainElasticity::init(const Scene&) {
  chain_ = dynamic_cast<const FramedChain*>(&body());
  if (!chain_) throw SceneError(origin(), "a FramedChain body for " + describe(), body().describe());
  const int segments = chain_->segmentCount();
  length_ = 0.0;
  for (int i = 0; i < segments; ++i) length_ += chain_->restLength(i);
  axial_.clear(), shear_.clear(), bending_.clear(), joint_bending_.assign(segments, Vec3::Zero());
  joint_rest_.assign(segments, Vec3::Zero());
  for (int i = 0; i < segments; ++i) {
    const Span& span = spanAt(0.5 * (chain_->nodeAbscissa(i) + chain_->nodeAbscissa(i + 1)));
    const FramedChain::Section& section = chain_->segmentSection(i);
    const double area = section.area(), second = section.secondMoment();
    const double E = span.youngs_modulus, G = E / (2.0 * (1.0 + span.poisson_ratio));
    axial_.push_back(E * area);
    shear_.push_back(shearCoefficient(span.poisson_ratio, section.inner_radius / section.radius) * G * area);
    bending_.push_back(Vec3(E * second, E * second, G * 2.0 * second));
  }
  for (int j = 1; j < segments; ++j) {
    // B_j / ℓ_j with B_j the two half segments in series: 1 / (l_{j−1}/(2B_{j−1}) + l_j/(2B_j)).
    const double la = chain_->restLength(j - 1), lb = chain_->restLength(j);
    joint_bending_[j] = (0.5 * la * bending_[j - 1].cwiseInverse() + 0.5 * lb * bending_[j].cwiseInverse()).cwiseInverse();
    const double node = chain_->nodeAbscissa(j) * length_;
    joint_rest_[j] = rest_from_initial_
                         ? geometry::rotationLog(chain_->initialFrame(j - 1).conjugate() * chain_->initialFrame(j))
                         : restTurn(node - 0.5 * la, node + 0.5 * lb);
  }
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
  const double axial = axial_[i], shear = shear_[i];
  const double energy = 0.5 * axial / l * (length - l) * (length - l) + 0.5 * shear * l * (d3 - t).squaredNorm();
  if (!forces) return energy;

  // ∂E/∂d3 = κGA l (d3 − t) = g, ∂E/∂t = −g; through t = e/|e|, ∂t/∂e = (I − t tᵀ)/|e|.
  const Vec3 g = shear * l * (d3 - t);
  const Vec3 dE_de = (axial / l * (length - l)) * t - (g - t * t.dot(g)) / length;
  VecX& B = *forces;
  const int a = chain.offset() + i, b = a + 1;
  B.segment<3>(3 * a) += dE_de;  // e = x_b − x_a: Q_a = +∂E/∂e, Q_b = −∂E/∂e
  B.segment<3>(3 * b) -= dE_de;
  chain.internalVelocities(B).segment<3>(3 * i) -= Vec3::UnitZ().cross(R.conjugate() * g);
  return energy;
}

double ChainElasticity::joint(const SceneState& s, int j, VecX* forces) const {
  const FramedChain& chain = *chain_;
  const Eigen::Quaterniond Ra = chain.orientation(s.q, j - 1), Rb = chain.orientation(s.q, j);
  const Vec3 phi = geometry::rotationLog(Ra.conjugate() * Rb);
  const Vec3 moment = joint_bending_[j].cwiseProduct(phi - joint_rest_[j]);  // m = B (φ − φ̄) / ℓ
  const double energy = 0.5 * (phi - joint_rest_[j]).dot(moment);
  if (!forces) return energy;
  Vec3 right, left;
  geometry::jacobianInverseTransposeTimes(phi, moment, right, left);
  auto torques = chain.internalVelocities(*forces);
  torques.segment<3>(3 * (j - 1)) += left;  // +J_l⁻ᵀ m
  torques.segment<3>(3 * j) -= right;       // −J_r⁻ᵀ m
  return energy;
}

void ChainElasticity::addJacobian(const SceneState& s, double k_factor, double, JacobianAccumulator& out) const {
  if (k_factor == 0.0) return;
  const FramedChain& chain = *chain_;
  const ConstPointsMap x = chain.block(s.q);
  const Eigen::Matrix3d I = Eigen::Matrix3d::Identity();
  for (int i = 0; i < chain.segmentCount(); ++i) {
    const double l = chain.restLength(i), ks = shear_[i] * l;
    const Vec3 e = (x.row(i + 1) - x.row(i)).transpose();
    const double r = e.norm();
    const Vec3 t = e / r;
    const Eigen::Quaterniond R = chain.orientation(s.q, i);
    const Vec3 d3 = R * Vec3::UnitZ(), tb = R.conjugate() * t, pd = d3 - t * t.dot(d3);
    const Eigen::Matrix3d P = I - t * t.transpose();
    const Eigen::Matrix3d Hee = axial_[i] / l * (t * t.transpose() + (1.0 - l / r) * P) +
                                ks / (r * r) * (pd * t.transpose() + t * pd.transpose() + t.dot(d3) * P);
    const Eigen::Matrix3d Hed = ks / r * P * R.toRotationMatrix() * geometry::skew(Vec3::UnitZ());
    const Eigen::Matrix3d Hdd =
        ks * (tb.z() * I - 0.5 * (tb * Vec3::UnitZ().transpose() + Vec3::UnitZ() * tb.transpose()));
    // k · K = −k · H over (x_a, x_b, δ): H_aa = H_bb = H_ee, H_ab = −H_ee, H_bδ = H_eδ, H_aδ = −H_eδ.
    const int a = chain.offset() + i, b = a + 1, f = chain.internalGroup(i);
    out.addBlock(a, a, -k_factor * Hee);
    out.addBlock(b, b, -k_factor * Hee);
    out.addBlockPair(b, a, k_factor * Hee);
    out.addBlock(f, f, -k_factor * Hdd);
    out.addBlockPair(b, f, -k_factor * Hed);
    out.addBlockPair(a, f, k_factor * Hed);
  }
  for (int j = 1; j < chain.segmentCount(); ++j) {
    const Vec3 phi = geometry::rotationLog(chain.orientation(s.q, j - 1).conjugate() * chain.orientation(s.q, j));
    const Eigen::Matrix3d Jl = geometry::leftJacobianInverse(phi), Jr = geometry::rightJacobianInverse(phi);
    const Eigen::Matrix3d B = joint_bending_[j].asDiagonal();
    const int ga = chain.internalGroup(j - 1), gb = chain.internalGroup(j);
    out.addBlock(ga, ga, -k_factor * (Jl.transpose() * B * Jl));
    out.addBlock(gb, gb, -k_factor * (Jr.transpose() * B * Jr));
    out.addBlockPair(ga, gb, k_factor * (Jl.transpose() * B * Jr));
  }
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
