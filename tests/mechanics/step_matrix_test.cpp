// The matrices of implicit steps, A = M − θh D − κh² K (step_matrix.hpp): the 3 × 3-block band LDLᵀ, the
// sparse path (CHOLMOD, or Eigen SimplicialLDLT without SuiteSparse) and the coupled-bodies path
// all solve like a dense factorization of the same symmetrised matrix; implicit integrators keep
// constraints through it.
//
// Tolerances: LDLᵀ without pivoting is backward stable for these matrices (M-dominated, κ(A)
// below 1e8 here), so solutions agree to κ ε ≈ 1e-8 relative at worst; 1e-9 is asserted on the
// well-conditioned cases (measured ~1e-14) and 1e-7 where stiffness dominates.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cstdio>
#include <limits>

#include "filum/core/scene_error.hpp"
#include "filum/geometry/spline_curve.hpp"
#include "filum/mechanics/block_band_ldlt.hpp"
#include "filum/mechanics/block_band_matrix.hpp"
#include "filum/mechanics/dynamic_spline.hpp"
#include "filum/mechanics/implicit_euler.hpp"
#include "filum/mechanics/step_matrix.hpp"
#include "support/finite_difference.hpp"
#include "support/force_field_check.hpp"
#include "support/mechanics_scenes.hpp"

namespace filum {
namespace {

using nlohmann::json;

/// A random symmetric matrix of order n with half bandwidth p (entries in [−1, 1]).
MatX randomSymmetricBand(int n, int p, int seed) {
  const Points noise = test::randomPoints(n * n / 3, 1.0, seed);
  MatX A = MatX::Zero(n, n);
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - p); j <= i; ++j) A(i, j) = A(j, i) = noise.data()[k++];
  return A;
}

/// S (half bandwidth p) as a BlockBandLdlt: scalar entries |i − j| <= p reach (p + 2)/3 blocks away.
void fillBand(const MatX& S, int p, mechanics::BlockBandLdlt& band) {
  const int n = static_cast<int>(S.rows());
  band.resize(n / 3, (p + 2) / 3);
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - p); j <= i; ++j) band.addLower(i, j, S(i, j));
}

TEST(BlockBandLdlt, SolvesSymmetricBandMatricesIncludingIndefiniteOnes) {
  // A random symmetric band matrix (half bandwidth 11, n = 60), once shifted to be positive
  // definite and once indefinite; compared with a dense LU.
  const int n = 60, p = 11;
  const MatX A = randomSymmetricBand(n, p, 5);
  for (double shift : {30.0, 0.5}) {
    const MatX S = A + shift * MatX::Identity(n, n);
    mechanics::BlockBandLdlt band;
    fillBand(S, p, band);
    ASSERT_EQ(band.factor(), "");
    VecX x = VecX::LinSpaced(n, -1.0, 2.0);
    const VecX b = x;
    band.solve(x);
    const VecX reference = S.fullPivLu().solve(b);
    const double kappa = S.jacobiSvd().singularValues()(0) / S.jacobiSvd().singularValues()(n - 1);
    EXPECT_LE((x - reference).norm(), 1e2 * kappa * 1e-16 * reference.norm()) << "shift " << shift;
  }
}

TEST(BlockBandLdlt, SolvesColumnsTogetherAsOneByOne) {
  // Several right-hand sides at once, zero above a first block row (as a contact row's column
  // is), give the same numbers bit for bit as solve() on each: the same operations in the same
  // order, and the skipped forward terms are products with exact zeros.
  const int n = 45, p = 8;
  const Points noise = test::randomPoints(n * n / 3, 1.0, 7);
  mechanics::BlockBandLdlt band;
  band.resize(n / 3, (p + 2) / 3);
  int k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = std::max(0, i - p); j <= i; ++j) band.addLower(i, j, noise.data()[k++] + (i == j ? 20.0 : 0.0));
  ASSERT_EQ(band.factor(), "");
  for (int first : {0, 4, 14}) {
    MatX columns = MatX::Zero(n, 5);
    const Points values = test::randomPoints(5 * (n - 3 * first), 1.0, 11 + first);  // (3× as many as used)
    columns.bottomRows(n - 3 * first) = Eigen::Map<const MatX>(values.data(), n - 3 * first, 5);
    MatX one_by_one = columns;
    for (int c = 0; c < 5; ++c) band.solve(one_by_one.col(c));
    band.solveColumns(columns, first);
    EXPECT_EQ(columns, one_by_one) << "first block row " << first;
  }
}

TEST(BlockBandLdlt, TheInverseBandIsTheDenseInversesBand) {
  // Takahashi's equations give A⁻¹'s blocks within the band without the rest; compared with the
  // dense inverse of the same matrix, positive definite and indefinite (as SolvesSymmetric...).
  // An inverse through a triangular factorization is accurate to γ_m κ(A) ‖A⁻¹‖ (Higham, Accuracy
  // and Stability of Numerical Algorithms, 2002, §14.3), γ_m ≈ m ε for sums of m terms: the
  // recurrence's entries gather at most n products (two triangular sweeps' worth of 3 × 3 blocks
  // across the band), so m = 3n with the factors' growth of order one (no pivoting: these blocks
  // are well scaled; the solve's test above holds it too).
  const int n = 60, p = 11;
  const MatX A = randomSymmetricBand(n, p, 13);
  for (double shift : {30.0, 0.5}) {
    const MatX S = A + shift * MatX::Identity(n, n);
    mechanics::BlockBandLdlt band;
    fillBand(S, p, band);
    ASSERT_EQ(band.factor(), "");
    const MatX inverse = S.fullPivLu().inverse();
    const double kappa = S.jacobiSvd().singularValues()(0) / S.jacobiSvd().singularValues()(n - 1);
    const double inverse_norm = 1.0 / S.jacobiSvd().singularValues()(n - 1);  // ‖A⁻¹‖₂ = 1/σ_min
    const int blocks = n / 3;
    // The band's own range, and wider ones (up to the whole matrix), into one vector reused as a
    // solver reuses it (its earlier contents in another layout), widening and narrowing: the
    // recurrence stays within the range asked for, and every block is still a triangular solve's
    // result (the bound above, which grows with n, holds for each).
    std::vector<Eigen::Matrix3d> z;
    for (int range : {0, band.range(), blocks - 1, band.range() + 1, 2 * band.range() + 3, band.range()}) {
      band.inverseBand(z, range);
      const int r = std::max(range, band.range());
      ASSERT_GE(z.size(), static_cast<std::size_t>(blocks * (r + 1)));
      double error = 0.0;
      for (int I = 0; I < blocks; ++I)
        for (int J = std::max(0, I - r); J <= I; ++J)
          error = std::max(error, (z[I * (r + 1) + (J - I + r)] - inverse.block<3, 3>(3 * I, 3 * J)).lpNorm<Eigen::Infinity>());
      EXPECT_LE(error, 3 * n * std::numeric_limits<double>::epsilon() * kappa * inverse_norm)
          << "shift " << shift << ", range " << range;
    }
  }
}

TEST(BlockBandLdlt, ReportsAZeroPivot) {
  mechanics::BlockBandLdlt band;
  band.resize(1, 0);
  band.addLower(0, 0, 1.0);
  band.addLower(1, 0, 1.0);
  band.addLower(1, 1, 1.0);  // second pivot 1 − 1·1 = 0
  band.addLower(2, 2, 1.0);
  EXPECT_NE(band.factor().find("pivot"), std::string::npos);
}

/// The symmetrised dense A of a triplet list.
MatX denseSymmetric(const Triplets& triplets, Eigen::Index n) {
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(triplets.begin(), triplets.end());
  const MatX dense = MatX(A);
  return 0.5 * (dense + dense.transpose());
}

/// Assembles the step matrix of the scene's fields at a perturbed state with h and solves a
/// random right-hand side with each choice of factorization; returns the relative differences
/// to a dense solve.
void expectSolversAgree(const json& components, double h, double tolerance, const std::string& expect_auto) {
  test::ThreadSpec spec;
  spec.control_points = 12;
  auto scene = test::loadThreadWith(spec, components);
  SceneState s = scene->state();
  const Points dq = test::randomPoints(scene->dofPointCount(), 0.005, 3);
  s.q += Eigen::Map<const VecX>(dq.data(), dq.size());
  Triplets triplets;
  TripletAccumulator accumulator(triplets);
  scene->addMassMatrix(1.0, accumulator);
  scene->addForceJacobian(s, -h * h, -h, accumulator);
  const Eigen::Index n = s.q.size();
  const VecX b = VecX::LinSpaced(n, -1.0, 1.0);
  const VecX reference = denseSymmetric(triplets, n).fullPivLu().solve(b);
  for (auto choice : {mechanics::LinearSolverChoice::Auto, mechanics::LinearSolverChoice::Band,
                      mechanics::LinearSolverChoice::Sparse}) {
    mechanics::StepMatrix A(choice);
    ASSERT_EQ(A.assemble(*scene, s, -h * h, -h), "");
    ASSERT_EQ(A.assemble(*scene, s, -h * h, -h), "");  // reassembly on the cached layout
    VecX x = b;
    A.solveAll(x);
    VecX y = b;
    A.solveBlock(0, y);
    const double error = (x - reference).norm() / reference.norm();
    std::printf("  %-60s %-40s relative difference %.1e\n", components.dump().substr(0, 60).c_str(), A.method().c_str(),
                error);
    EXPECT_LE(error, tolerance) << A.method();
    EXPECT_EQ(x, y) << "solveBlock and solveAll differ for one body";
    if (choice == mechanics::LinearSolverChoice::Auto) {
      EXPECT_NE(A.method().find(expect_auto), std::string::npos) << A.method();
    }
  }
}

TEST(BlockBandMatrix, SupportBlocksAddAsTheirBlocksOneByOne) {
  // addSupportBlocks' direct path (one layout check per support) against the interface's
  // default (addBlock, addBlockPair per pair): the same additions, so equal bit for bit; a
  // support that reaches past the band falls back and counts its misfits.
  const int first = 5, points = 9;
  Eigen::Matrix3d lower[10];
  for (int k = 0; k < 10; ++k) lower[k] = Eigen::Matrix3d::Random();
  for (int k : {0, 2, 5, 9}) lower[k] = lower[k] + lower[k].transpose().eval();  // diagonal blocks symmetric
  mechanics::BlockBandMatrix direct, reference;
  direct.resize(first, points, 3);
  reference.resize(first, points, 3);
  direct.addSupportBlocks(first + 2, 4, lower);
  reference.JacobianAccumulator::addSupportBlocks(first + 2, 4, lower);
  for (int i = 0; i < points; ++i)
    for (int j = std::max(0, i - 3); j <= std::min(points - 1, i + 3); ++j)
      EXPECT_EQ(direct.block(i, j), reference.block(i, j)) << "block " << i << ", " << j;
  EXPECT_EQ(direct.misfits(), 0);
  EXPECT_EQ(direct.neededRange(), 3);
  mechanics::BlockBandMatrix narrow;
  narrow.resize(first, points, 2);
  narrow.addSupportBlocks(first + 2, 4, lower);
  EXPECT_EQ(narrow.misfits(), 2);  // pair (3, 0) and its transpose
  EXPECT_EQ(narrow.neededRange(), 3);
}

TEST(StepMatrix, BandSparseAndDenseSolvesAgree) {
  const json local = json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
                                  {{"type", "CurvatureBending"}, {"youngs_modulus", 2e9}},
                                  {{"type", "ViscousDamping"}, {"coefficient", 3.0}},
                                  {{"type", "RayleighDamping"}, {"stiffness_coefficient", 1e-4}}});
  expectSolversAgree(local, 1e-5, 1e-9, "band (half bandwidth 11)");
  expectSolversAgree(local, 1e-3, 1e-7, "band (half bandwidth 11)");  // stiffness-dominated
  // The paper's global stretching couples every control point through its rank-one term
  // Ê''(l) ∇l ∇lᵀ: auto keeps the band and solves with Sherman–Morrison.
  const json global = json::array({{{"type", "GlobalStretching"}, {"youngs_modulus", 2e9}},
                                   {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}}});
  expectSolversAgree(global, 1e-5, 1e-9, "band (half bandwidth 11) + rank 1 (Sherman-Morrison-Woodbury)");
  expectSolversAgree(global, 1e-3, 1e-7, "band (half bandwidth 11) + rank 1 (Sherman-Morrison-Woodbury)");
}

TEST(StepMatrix, BandAssemblyEqualsTripletAssemblyForEveryForceField) {
  // Direct band assembly (StepMatrix as the JacobianAccumulator) against the reference triplet
  // assembly (TripletAccumulator, then a dense symmetrised matrix) of M − h D − h² K, field by
  // field, at a random state with random velocities, h = 1 ms (stiffness-dominated at 2 GPa).
  // Tolerance 1e-12 of the largest entry: the two assemblies add the same terms in another order
  // (≤ 100 terms per entry: 1e2 ε ≈ 2e-14 relative), and the band matrix is read back from its
  // factors L D Lᵀ, whose backward error is bounded by (p + 1) ε |L||D||Lᵀ| ≈ 2.7e-15 |L||D||Lᵀ|
  // for p = 11 (Higham, Accuracy and Stability, Thm 10.3 without pivoting): 1e-12 leaves a growth
  // |L||D||Lᵀ| / |A| of up to ~300, far above what an M-dominated matrix shows.
  const double h = 1e-3;
  const json fields[] = {
      {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}},
      {{"type", "CurvatureBending"}, {"youngs_modulus", 2e9}},
      {{"type", "ParametricBending"}, {"youngs_modulus", 2e9}},
      {{"type", "GlobalStretching"}, {"youngs_modulus", 2e9}},
      {{"type", "SpringForceField"}, {"stretch_stiffness", 50.0}, {"bend_stiffness", 0.01}, {"damping", 1e-3}},
      {{"type", "ViscousDamping"}, {"coefficient", 3.0}},
      {{"type", "RayleighDamping"}, {"stiffness_coefficient", 1e-4}},
  };
  for (const json& field : fields) {
    test::ThreadSpec spec;
    spec.control_points = 14;
    json components = json::array({field});
    if (field["type"] == "RayleighDamping") components.push_back({{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 2e9}});
    auto scene = test::loadThreadWith(spec, components);
    SceneState s = scene->state();
    const Points dq = test::randomPoints(scene->dofPointCount(), 0.003, 11);
    const Points dv = test::randomPoints(scene->dofPointCount(), 0.5, 12);
    s.q += Eigen::Map<const VecX>(dq.data(), dq.size());
    s.v += Eigen::Map<const VecX>(dv.data(), dv.size());
    Triplets triplets;
    TripletAccumulator reference(triplets);
    scene->addMassMatrix(1.0, reference);
    scene->addForceJacobian(s, -h * h, -h, reference);
    const MatX expected = denseSymmetric(triplets, s.q.size());
    mechanics::StepMatrix A;
    for (int pass = 0; pass < 2; ++pass) {  // the second assembly copies the cached constant band
      ASSERT_EQ(A.assemble(*scene, s, -h * h, -h), "") << field.dump();
      const double error = (A.assembledMatrix() - expected).cwiseAbs().maxCoeff() / expected.cwiseAbs().maxCoeff();
      std::printf("  %-24s %-58s max difference %.1e of the largest entry\n", field["type"].get<std::string>().c_str(),
                  A.method().c_str(), error);
      EXPECT_LE(error, 1e-12) << field.dump();
    }
  }
}

/// Test-only force field coupling two bodies: a spring of stiffness k between P(1) of its own
/// body and P(0) of the body at node "other" (Q = −∂E/∂q with E = ½ k |P_a(1) − P_b(0)|²).
class CouplingSpring final : public ForceField {
 public:
  explicit CouplingSpring(double k) : k_(k) {}
  std::string typeName() const override { return "CouplingSpring"; }
  void addForce(const SceneState& s, VecX& B) const override {
    const Vec3 f = k_ * (end(s, *b_, 0.0, row_b_) - end(s, body(), 1.0, row_a_));  // on a; −f on b
    scatter(body(), row_a_, f, B);
    scatter(*b_, row_b_, -f, B);
  }
  double potentialEnergy(const SceneState& s) const override {
    return 0.5 * k_ * (end(s, *b_, 0.0, row_b_) - end(s, body(), 1.0, row_a_)).squaredNorm();
  }
  void addJacobian(const SceneState&, double k_factor, double, JacobianAccumulator& out) const override {
    // Q_a = k (P_b − P_a) b_a, Q_b = −k (P_b − P_a) b_b:  ∂Q/∂q = −k (w wᵀ) ⊗ I, w = (b_a, −b_b).
    struct Term {
      int point;
      double weight;
    };
    std::vector<Term> w;
    for (int j = 0; j < row_a_.count; ++j) w.push_back({body().offset() + row_a_.first + j, row_a_.value[j]});
    for (int j = 0; j < row_b_.count; ++j) w.push_back({b_->offset() + row_b_.first + j, -row_b_.value[j]});
    for (const Term& i : w)
      for (const Term& j : w)
        out.addIsotropic(i.point, j.point, -k_factor * k_ * i.weight * j.weight);
  }
  bool hasJacobian() const override { return true; }

 private:
  void init(const Scene& scene) override {
    b_ = const_cast<Scene&>(scene).bodyAt("other");
    if (!b_) throw SceneError(origin(), "a node named 'other'");
    body().curve()->basis().evaluate(1.0, row_a_);
    b_->curve()->basis().evaluate(0.0, row_b_);
  }
  static Vec3 end(const SceneState& s, const MechanicalState& m, double, const geometry::BasisRow& row) {
    return geometry::curvePoint(row, m.block(s.q));
  }
  static void scatter(const MechanicalState& m, const geometry::BasisRow& row, const Vec3& f, VecX& B) {
    for (int j = 0; j < row.count; ++j) m.block(B).row(row.first + j) += row.value[j] * f.transpose();
  }
  double k_;
  const MechanicalState* b_ = nullptr;
  geometry::BasisRow row_a_, row_b_;
};

std::unique_ptr<Scene> coupledThreads(const json& integrator, double dt) {
  Factory factory = app::makeFactory();
  factory.add("CouplingSpring", "test only", [](const Params& p) { return std::make_unique<CouplingSpring>(p.positive("stiffness")); });
  auto thread = [](const char* name, double x0) {
    return json{{"name", name},
                {"components",
                 json::array({{{"type", "DynamicSpline"},
                               {"control_points", {{"from", {x0, 0.0, 0.0}}, {"to", {x0 + 0.1, 0.0, 0.0}}, {"count", 10}}},
                               {"mass", 2.86e-6}},
                              {{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 1e8}},
                              {{"type", "ParametricBending"}, {"youngs_modulus", 1e8}},
                              {{"type", "FixedPointConstraint"}, {"abscissa", x0 == 0.0 ? 0.0 : 1.0}}})}};
  };
  json document = {{"name", "coupled threads"}, {"dt", dt}, {"gravity", {0.0, 0.0, -9.81}}, {"integrator", integrator}};
  json first = thread("first", 0.0), second = thread("other", 0.1);
  first["components"].push_back({{"type", "CouplingSpring"}, {"stiffness", 50.0}});
  document["nodes"] = json::array({first, second});
  return loadScene(document, "coupled threads", factory);
}

TEST(StepMatrix, CoupledBodiesGoToOneSparseFactorizationAndKeepTheirConstraints) {
  // Two threads end to end, each fixed at its outer end, joined by a stiff spring: the implicit
  // step couples them (coupled() is true) and the constraint solver solves through solveAll.
  // The coupling spring's derivatives first pass the generic force-field check.
  auto scene = coupledThreads({{"type", "ImplicitEuler"}}, 1e-3);
  const ForceField* spring = nullptr;
  for (const ForceField* f : scene->forceFields())
    if (f->typeName() == "CouplingSpring") spring = f;
  ASSERT_NE(spring, nullptr);
  SceneState moved = scene->state();
  const Points dq = test::randomPoints(scene->dofPointCount(), 0.005, 9);
  moved.q += Eigen::Map<const VecX>(dq.data(), dq.size());
  test::ForceFieldCheck check;
  check.h = 1e-7;
  check.tolerance = 1e-7;
  test::expectForceFieldConsistent(*spring, moved, check);
  const auto& integrator = dynamic_cast<const mechanics::ImplicitEuler&>(scene->integrator());
  for (int k = 0; k < 200; ++k) {
    const StepReport report = scene->step();
    ASSERT_TRUE(report.ok) << report.message;
  }
  std::printf("  coupled: %s, %ld Newton iterations over %ld solves\n", integrator.solver().matrix().method().c_str(),
              integrator.solver().totalIterations(), integrator.solver().solves());
  EXPECT_TRUE(integrator.solver().matrix().coupled());
  EXPECT_LE(scene->constraintViolation(scene->state()).cwiseAbs().maxCoeff(), 1e-9);
  // The joint sagged under gravity and the two ends stayed together: the threads span exactly
  // their length, so the spring (k = 50 N/m) carries the sagging string's tension, ~5e-4 N: a
  // gap of ~1e-5 m.
  const auto end = [&](int body, double s) {
    const auto& spline = *scene->bodies()[body]->curve();
    return geometry::curvePoint(spline.basis(), spline.block(scene->state().q), s);
  };
  EXPECT_LT(end(0, 1.0).z(), -1e-3);
  EXPECT_LT((end(0, 1.0) - end(1, 0.0)).norm(), 5e-5);
}

TEST(StepMatrix, ImplicitMidpointWithAFixedPointTracksRungeKutta4) {
  // A hanging thread held at one end: the implicit midpoint rule (constraints through A⁻¹) and
  // RK4 (through M⁻¹) from the same start agree to the midpoint's O(h²) error after 20 ms.
  auto run = [](const char* type, double dt) {
    test::ThreadSpec spec;
    spec.control_points = 10;
    spec.integrator = {{"type", type}};
    spec.dt = dt;
    auto scene = test::loadThreadWith(spec, json::array({{{"type", "GreenLagrangeStretching"}, {"youngs_modulus", 1e6}},
                                                         {{"type", "ParametricBending"}, {"youngs_modulus", 1e6}},
                                                         {{"type", "FixedPointConstraint"}, {"abscissa", 0.0}, {"stabilization", 50.0}}}));
    for (int k = 0; k < static_cast<int>(std::lround(0.02 / dt)); ++k) EXPECT_TRUE(scene->step().ok);
    return scene->state().q;
  };
  const VecX reference = run("RungeKutta4", 1e-6);
  const double coarse = (run("ImplicitMidpoint", 4e-5) - reference).lpNorm<Eigen::Infinity>();
  const double fine = (run("ImplicitMidpoint", 2e-5) - reference).lpNorm<Eigen::Infinity>();
  std::printf("  midpoint vs RK4 after 20 ms: %.3e m (dt 4e-5), %.3e m (dt 2e-5), ratio %.2f\n", coarse, fine, coarse / fine);
  EXPECT_LT(fine, 1e-4);  // the thread falls ~2 mm in 20 ms
  EXPECT_NEAR(coarse / fine, 4.0, 0.6);
}

}  // namespace
}  // namespace filum
