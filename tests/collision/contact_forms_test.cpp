// The contact sweeps through an implicit step matrix in their two forms (LagrangeMultiplierSolver
// "contact_form"): W assembled, and factored (u = A⁻¹Lᵀλ kept, (Wλ)_r = L_r·u). They are the same
// projected Gauss–Seidel iteration on the same operator — the same sweeps, row by row — and give
// the same step up to round-off: from one state of threads.json in the middle of its impact
// (eleven vessel loops, 49 contacts with friction, 33 equality rows), one step each way.
#include <gtest/gtest.h>

#include <cmath>
#include <iostream>

#include "collision_scenes.hpp"

namespace filum::collision {
namespace {

const std::string kThreads = std::string(FILUM_SOURCE_DIR) + "/apps/scenes/threads.json";

std::unique_ptr<Scene> threadsWith(const std::string& form) {
  nlohmann::json document = readJsonFile(kThreads);
  // Both run the full number of sweeps (a tolerance below round-off is never met), so that the
  // two forms do the same iteration count.
  document["constraint_solver"] = {{"type", "LagrangeMultiplierSolver"}, {"contact_form", form},
                                   {"contact_iterations", 300}, {"contact_tolerance", 1e-300}};
  return loadScene(document, kThreads, app::makeFactory());
}

TEST(ContactForms, FactoredAndAssembledSweepsTakeTheSameStep) {
  // 142 steps: the loops swing into each other (contacts from step ~125).
  auto reference = threadsWith("assembled");
  for (int k = 0; k < 142; ++k) ASSERT_TRUE(reference->step().ok);
  const SceneState start = reference->state();

  auto assembled = threadsWith("assembled");
  auto factored = threadsWith("factored");
  assembled->init();
  factored->init();
  assembled->setState(start);
  factored->setState(start);
  ASSERT_TRUE(assembled->step().ok);
  ASSERT_TRUE(factored->step().ok);
  const auto& pipeline = test::pipelineOf(*factored);
  ASSERT_GT(pipeline.contacts().size(), 20u) << "not a contact step";
  ASSERT_EQ(test::pipelineOf(*assembled).contacts().size(), pipeline.contacts().size());

  const double dq = (assembled->state().q - factored->state().q).lpNorm<Eigen::Infinity>();
  const double dv = (assembled->state().v - factored->state().v).lpNorm<Eigen::Infinity>();
  const double motion = (factored->state().q - start.q).lpNorm<Eigen::Infinity>();
  std::cout << "  " << pipeline.contacts().size() << " contacts; the two forms' steps differ by " << dq
            << " m in position (the step moved " << motion << " m), " << dv << " m/s in velocity\n";
  // Round-off: the forms sum the same products in another order, ε = 1.1e-16 relative per
  // operation on accelerations of |a| <= |β|∞ ~ 1e3 m/s²; the sweeps are a contraction on the
  // normal rows (W positive definite there) and a projection on the friction discs (1-Lipschitz),
  // so the differences do not grow from sweep to sweep beyond the ~1e3 terms that feed one row:
  // |Δa| <= 1e3 · 1e3 · ε ~ 1e-10 m/s², so |Δv| = h |Δa| ~ 1e-13 m/s and |Δq| = h² |Δa| ~ 1e-16 m.
  // The bounds allow a thousand times that (conditioning of W through the stiff loops), still
  // 1e-10 of the step's motion.
  EXPECT_LT(dq, 1e-13);
  EXPECT_LT(dv, 1e-10);
}

}  // namespace
}  // namespace filum::collision
