// StepMatrix: the matrix of an implicit step, A = M − θh D − κh² K (M the mass matrices, K = ∂Q/∂q
// and D = ∂Q/∂q̇ the force Jacobians of ForceField::addJacobian), assembled from triplets and
// factored, body by body when no force couples two bodies. It is the BlockInverse the constraint
// solver works through during an implicit step, so constraints keep the acceleration
// decomposition of paper §4 with A in place of M.
//
// Factorization per block (DESIGN.md "Numbers that matter"):
//   - band (BandedLdlt, O(n d²)) when the block's half bandwidth is small — one spline with local
//     energies: 3d + 2 = 11 for the cubic B-spline;
//   - sparse (SparseLdlt: CHOLMOD, or Eigen SimplicialLDLT without SuiteSparse) for a wide band
//     (the paper's global stretching couples every control point) and for the whole scene when a
//     force couples bodies (then coupled() is true and solves go through solveAll).
// The triplets are symmetrised, A ← (A + Aᵀ)/2: dissipative forces may have a non-symmetric
// Jacobian (a dashpot's direction depends on positions); Newton then converges a little slower
// but to the same solution, since the residual is evaluated exactly.
//
// The structure (band widths, sparsity pattern) is analysed on the first assembly and redone only
// when a triplet does not fit it; in the steady state assembling and factoring allocate nothing on
// the band path, and the triplets are read once.
#pragma once

#include <string>
#include <vector>

#include "filum/core/block_inverse.hpp"
#include "filum/core/params.hpp"
#include "filum/mechanics/banded_ldlt.hpp"
#include "filum/mechanics/sparse_ldlt.hpp"

namespace filum {
class Scene;
}

namespace filum::mechanics {

/// Which factorization a StepMatrix uses: Auto picks band or sparse per block from its width.
enum class LinearSolverChoice { Auto, Band, Sparse };

/// "linear_solver": "auto" (default) | "band" | "sparse" from integrator parameters.
LinearSolverChoice linearSolverFromParams(const Params& p);

class StepMatrix final : public BlockInverse {
 public:
  /// Auto uses the band solver when a body's half bandwidth is at most this (3 d + 2 for
  /// degree d <= 5 is at most 17; wider means a non-local energy).
  static constexpr int kAutoBandLimit = 32;

  explicit StepMatrix(LinearSolverChoice choice = LinearSolverChoice::Auto) : choice_(choice) {}

  /// A := symmetric part of the sum of `triplets` (global 3N indices of `scene`), factored.
  /// Returns "" on success, else why the factorization failed.
  std::string assemble(const Scene& scene, const Triplets& triplets);

  void solveBlock(int body, Eigen::Ref<VecX> x) const override;
  bool coupled() const override { return coupled_; }
  void solveAll(Eigen::Ref<VecX> x) const override;
  /// Changes at every assembly (a constraint solver may keep A⁻¹Lᵀ while it does not).
  long revision() const override { return revision_; }

  /// How the blocks are factored, e.g. "band (half bandwidth 11)" or "CHOLMOD supernodal LLt".
  std::string method() const;

 private:
  struct Block {
    int first = 0;  // first global coordinate
    int size = 0;   // coordinates
    bool band = true;
    int half_bandwidth = 0;
    BandedLdlt band_factor;
    SparseLdlt sparse;
    SparseLdlt::Matrix lower;        // lower triangle of A (sparse blocks)
    std::vector<long long> keys;     // (row, col) of each triplet routed here, as of the last analysis
    std::vector<int> slots;          // where each of those triplets lands in lower.valuePtr()
    std::size_t routed = 0;          // triplets routed here in the current assembly
    bool pattern_ok = true;          // the current triplets match keys so far
  };

  /// Works out a new layout (blocks, band widths, coupling) from the triplets.
  void analyse(const Scene& scene, const Triplets& triplets);
  /// Adds the triplets into the current layout; false when one does not fit it.
  bool scatter(const Triplets& triplets);
  /// Rebuilds a sparse block's matrix and slot table from this assembly's triplets.
  void rebuildSparse(Block& block, const Triplets& triplets);

  LinearSolverChoice choice_;
  long revision_ = 0;
  bool coupled_ = false;
  std::vector<Block> blocks_;
  std::vector<int> body_block_;     // block of each body
  std::vector<int> coordinate_body_;  // body of each global coordinate
  std::vector<int> wanted_width_;   // per body: half bandwidth seen in this assembly
  std::vector<Eigen::Triplet<double>> scratch_;  // lower triplets for a sparse rebuild
};

}  // namespace filum::mechanics
