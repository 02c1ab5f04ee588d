#include "filum/mechanics/spring_force_field.hpp"

#include <algorithm>

#include "filum/core/scene.hpp"
#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_point_mapping.hpp"
#include "filum/mechanics/dynamic_spline.hpp"

namespace filum::mechanics {

SpringForceField::SpringForceField(double stretch_stiffness, double bend_stiffness, double damping, int samples)
    : stretch_stiffness_(stretch_stiffness), bend_stiffness_(bend_stiffness), damping_(damping), samples_(samples) {}

std::unique_ptr<SpringForceField> SpringForceField::fromParams(const Params& p) {
  return std::make_unique<SpringForceField>(p.positive({"stretch_stiffness", "N/m"}), p.nonNegative({"bend_stiffness", "N/m"}, 0.0),
                                            p.nonNegative({"damping", "N·s/m"}, 0.0), p.has("samples") ? p.integer("samples", 3, 100000, "spring end points along the curve; each step evaluates them all") : 0);
}

void SpringForceField::init(const Scene&) {
  const auto* spline = dynamic_cast<const DynamicSpline*>(&body());
  if (!spline) throw SceneError(origin(), "a DynamicSpline body for " + describe(), body().describe());
  if (samples_ == 0) samples_ = 2 * spline->pointCount();
  const std::vector<double> abscissas = geometry::uniformAbscissas(samples_);
  ends_.resize(samples_);
  for (int k = 0; k < samples_; ++k) ends_[k].attach(*spline, abscissas[k]);
  x_.resize(samples_, 3);
  v_.resize(samples_, 3);
  f_.resize(samples_, 3);
  sample(spline->initialPositions(), x_);
  // A cut curve (CurveBasis::cuts): no spring joins samples of two strands (a sample at a cut
  // belongs to the strand after it, as evaluate does).
  const std::vector<double> cuts = spline->basis().cuts();
  auto strand = [&](int k) {
    const double s = ends_[k].abscissa();
    return static_cast<int>(std::upper_bound(cuts.begin(), cuts.end(), s) - cuts.begin());
  };
  springs_.clear();
  for (int gap = 1; gap <= 2; ++gap) {
    const double k = gap == 1 ? stretch_stiffness_ : bend_stiffness_;
    if (k == 0.0) continue;
    for (int a = 0; a + gap < samples_; ++a)
      if (strand(a) == strand(a + gap)) springs_.push_back({a, a + gap, k, (x_.row(a + gap) - x_.row(a)).norm()});
  }
}

void SpringForceField::sample(ConstPointsRef q, Points& x) const {
  for (int k = 0; k < samples_; ++k) ends_[k].apply(q, x.row(k));
}

void SpringForceField::sampleVelocities(ConstPointsRef q, ConstPointsRef v, Points& out) const {
  for (int k = 0; k < samples_; ++k) ends_[k].applyJ(q, v, out.row(k));
}

void SpringForceField::addForce(const SceneState& s, VecX& B) const {
  const ConstPointsMap q = body().block(s.q);
  sample(q, x_);
  sampleVelocities(q, body().block(s.v), v_);
  f_.setZero();
  for (const Spring& spring : springs_) {
    const Eigen::RowVector3d d = x_.row(spring.b) - x_.row(spring.a);
    const double l = d.norm();
    if (l == 0.0) continue;  // coincident samples: direction undefined, no force
    const Eigen::RowVector3d u = d / l;
    const double rate = (v_.row(spring.b) - v_.row(spring.a)).dot(u);
    const Eigen::RowVector3d f = (spring.stiffness * (l - spring.rest) + damping_ * rate) * u;
    f_.row(spring.a) += f;
    f_.row(spring.b) -= f;
  }
  PointsMap Q = body().block(B);
  for (int k = 0; k < samples_; ++k) ends_[k].applyJT(q, f_.row(k), Q);  // Q += Jₖᵀ fₖ
}

double SpringForceField::potentialEnergy(const SceneState& s) const {
  sample(body().block(s.q), x_);
  double e = 0.0;
  for (const Spring& spring : springs_) {
    const double stretch = (x_.row(spring.b) - x_.row(spring.a)).norm() - spring.rest;
    e += 0.5 * spring.stiffness * stretch * stretch;
  }
  return e;
}

void SpringForceField::addJacobian(const SceneState& s, double k_factor, double d_factor,
                                   JacobianAccumulator& out) const {
  const ConstPointsMap q = body().block(s.q);
  sample(q, x_);
  sampleVelocities(q, body().block(s.v), v_);
  for (const Spring& spring : springs_) {
    const Vec3 d = (x_.row(spring.b) - x_.row(spring.a)).transpose();
    const double l = d.norm();
    if (l == 0.0) continue;  // no force, no Jacobian (as in addForce)
    const Vec3 u = d / l;
    const Vec3 dv = (v_.row(spring.b) - v_.row(spring.a)).transpose();
    const double rate = dv.dot(u);
    const Eigen::Matrix3d uu = u * u.transpose();
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - uu;
    // G = ∂f/∂d (stiffness, geometric and dashpot-rotation terms), G_v = ∂f/∂Δv.
    const Eigen::Matrix3d G = spring.stiffness * uu + ((spring.stiffness * (l - spring.rest) + damping_ * rate) / l) * P +
                              (damping_ / l) * u * (dv.transpose() * P);
    const Eigen::Matrix3d block = k_factor * G + d_factor * damping_ * uu;
    // ∂F_k/∂x_m = ±block for k, m ∈ {a, b}: + when k ≠ m.
    const int ends[2] = {spring.a, spring.b};
    for (int kk = 0; kk < 2; ++kk)
      for (int mm = 0; mm < 2; ++mm) {
        const double sign = kk == mm ? -1.0 : 1.0;
        ends_[ends[kk]].forEachWeight([&](int i, double wi) {
          ends_[ends[mm]].forEachWeight([&](int j, double wj) { out.addBlock(i, j, (sign * wi * wj) * block); });
        });
      }
  }
}

}  // namespace filum::mechanics
