// StepMatrix: the matrix of an implicit step, A = M − θh D − κh² K (M the mass matrices, K = ∂Q/∂q
// and D = ∂Q/∂q̇ the force Jacobians of ForceField::addJacobian), assembled in place and factored,
// body by body when no force couples two bodies. It is the BlockInverse the constraint solver
// works through during an implicit step, so constraints keep the acceleration decomposition of
// paper §4 with A in place of M.
//
// Direct band assembly (docs/architecture.md, "Numbers that matter"). StepMatrix is the JacobianAccumulator
// the bodies and force fields write to: a 3 × 3 block lands straight in its body's band, with no
// triplet list, scatter or sort. Per block:
//   - band (BlockBandLdlt: LDLᵀ by 3 × 3 blocks, O(n d²)): the half bandwidth comes from the
//     body, 3d + 2 for a spline of degree d (11 for the cubic B-spline); the terms that do not change during a run — M ⊗ I₃,
//     and the constant Jacobians (ForceField::jacobianIsConstant: parametric bending, viscous
//     damping) at this step size — are assembled once into a constant band and copied in;
//   - band + low rank: a global energy's rank-one part σ u uᵀ (GlobalStretching) is kept apart
//     and solved with the Sherman–Morrison–Woodbury formula
//       (B + U Σ Uᵀ)⁻¹ x = y − Z (Σ⁻¹ + Uᵀ Z)⁻¹ Uᵀ y,   y = B⁻¹ x, Z = B⁻¹ U,
//     one extra band solve per rank-one term instead of a dense block;
//   - sparse (SparseLdlt: CHOLMOD, or Eigen SimplicialLDLT without SuiteSparse) when the user asks
//     for it, when a body declares no band, and for the whole scene when a force couples bodies
//     (then coupled() is true and solves go through solveAll); entries are collected as triplets
//     and scattered into the pattern analysed on the first assembly (symbolic analysis once).
// Entries are symmetrised, A ← (A + Aᵀ)/2: dissipative forces may have a non-symmetric Jacobian
// (a dashpot's direction depends on positions); Newton then converges a little slower but to the
// same solution, since the residual is evaluated exactly.
//
// Bodies with internal DOFs (a rod's frame rotations, in triples: JacobianAccumulator's groups
// after the points) have them in their own block, at the slots the body chooses
// (MechanicalState::stepSlotOfPoint/OfInternal: a rod interleaves x0, R0, x1, R1, ... so that its
// block stays a band). Solves then gather the block's values from the points and the internal
// triples and scatter them back. A solve on points only (solveBlock, solveAll on 3N values: the
// constraint solver's W = L A⁻¹ Lᵀ) pads the internal DOFs with zero force and returns the
// points' part, (A⁻¹)_pp; addInternalResponse gives the internal DOFs' part of the same solve.
//
// The layout (band widths, coupling) is worked out on the first assembly and again only when an
// entry does not fit it; in the steady state assembling and factoring allocate nothing.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Cholesky>

#include "filum/core/block_inverse.hpp"
#include "filum/core/jacobian_accumulator.hpp"
#include "filum/core/params.hpp"
#include "filum/mechanics/block_band_ldlt.hpp"
#include "filum/mechanics/sparse_ldlt.hpp"

namespace filum {
class Scene;
struct SceneState;
}  // namespace filum

namespace filum::mechanics {

/// Which factorization a StepMatrix uses: Auto picks band or sparse per block from its width.
enum class LinearSolverChoice { Auto, Band, Sparse };

/// "linear_solver": "auto" (default) | "band" | "sparse" from integrator parameters.
LinearSolverChoice linearSolverFromParams(const Params& p);

class StepMatrix final : public BlockInverse, public JacobianAccumulator {
 public:
  /// Auto uses the band solver when a body's half bandwidth is at most this (3 d + 2 for
  /// degree d <= 5 is at most 17; wider means a non-local energy).
  static constexpr int kAutoBandLimit = 32;

  explicit StepMatrix(LinearSolverChoice choice = LinearSolverChoice::Auto) : choice_(choice) {}

  /// A := M + k_factor·K + d_factor·D of `scene` at state s (k_factor = −κh², d_factor = −θh),
  /// symmetrised and factored. Returns "" on success, else why the factorization failed.
  std::string assemble(const Scene& scene, const SceneState& s, double k_factor, double d_factor);

  // BlockInverse
  /// x: the body's 3 n point values (internal DOFs padded with zero force, see the header).
  void solveBlock(int body, Eigen::Ref<VecX> x) const override;
  /// Through the band's factors once for all the columns (a contiguous band block without
  /// rank-one terms); column by column otherwise.
  void solveBlockColumns(int body, Eigen::Ref<MatX> x, int first_point) const override;
  bool coupled() const override { return coupled_; }
  /// x: 3 N point values (internal DOFs padded with zero), or 3 G values in group order (points,
  /// then internal triples: the whole step matrix).
  void solveAll(Eigen::Ref<VecX> x) const override;
  /// a (velocity layout) += the internal DOFs' part of A⁻¹ [f; 0] for point forces f (3N).
  void addInternalResponse(Eigen::Ref<const VecX> point_forces, VecX& a) const override;
  /// Changes at every assembly (a constraint solver may keep A⁻¹Lᵀ while it does not).
  long revision() const override { return revision_; }
  /// A band block without rank-one terms, bodies not coupled: its band as assembled.
  bool bandBlocks(int body, BandBlocks& out) const override;
  bool inverseBandBlocks(int body, int range, std::vector<Eigen::Matrix3d>& out) const override;

  // JacobianAccumulator (called by the bodies and force fields during assemble()).
  void addBlock(int i, int j, const Eigen::Matrix3d& block) override;
  void addBlockPair(int i, int j, const Eigen::Matrix3d& block) override;
  void addSupportBlocks(int first, int count, const Eigen::Matrix3d* lower) override;
  void addEntry(int row, int col, double value) override;
  void addIsotropic(int i, int j, double value) override;
  void addRankOne(int first, ConstPointsRef u, double factor) override;

  /// True when the last assembly was laid out for this scene's bodies and points.
  bool laidOutFor(const Scene& scene) const;

  /// How the blocks are factored, e.g. "band (half bandwidth 11)" or "CHOLMOD supernodal LLt".
  std::string method() const;
  /// Times the layout was worked out (1 in a steady run: the first assembly).
  long layouts() const { return layouts_; }
  /// The dense matrix A the blocks hold (band blocks from their factors L D Lᵀ plus the rank-one
  /// terms, sparse blocks from their lower triangle), 3N × 3N: for tests and diagnostics.
  MatX assembledMatrix() const;

 private:
  struct Block {
    int first_point = 0;  // first global group (a contiguous block: its slots are its groups in order)
    int points = 0;       // slots of the block (points and internal triples)
    int point_slots = 0;  // of them, points
    bool contiguous = true;           // slot k is group first_point + k
    std::vector<int> group_of_slot;   // otherwise: the global group of each slot
    mutable VecX work;                // gathered values of a solve (non-contiguous blocks)
    bool band = true;
    int range = 0;  // band blocks: largest |i − j| of coupled points; half bandwidth 3 range + 2
    BlockBandLdlt band_factor;
    BlockBandLdlt band_matrix;  // A's band as assembled (band_factor is factored in place)
    BlockBandLdlt constant;  // band blocks: M + constant Jacobians at constant_key_ (never factored)
    // Rank-one terms σ_k u_k u_kᵀ of this assembly (band blocks; Sherman–Morrison–Woodbury).
    MatX low_rank;        // 3 points × capacity: the u_k as columns
    VecX sigma;           // σ_k
    int rank = 0;         // terms in this assembly
    MatX solved_low_rank;  // Z = B⁻¹ U
    MatX capacitance;      // Σ⁻¹ + Uᵀ Z (rank × rank)
    Eigen::LDLT<MatX> capacitance_factor;
    mutable VecX projection;  // Uᵀ y of a solve
    mutable VecX correction;  // C⁻¹ Uᵀ y
    // Sparse blocks.
    SparseLdlt sparse;
    SparseLdlt::Matrix lower;     // lower triangle of A
    std::vector<long long> keys;  // (row, col) of each triplet routed here, as of the last analysis
    std::vector<int> slots;       // where each of those triplets lands in lower.valuePtr()
    std::size_t routed = 0;       // triplets routed here in the current assembly
    bool pattern_ok = true;       // the current triplets match keys so far
  };

  /// Works out a new layout (blocks, band widths, coupling) from the bodies and what the last
  /// assembly needed (wanted_range_, wanted_coupling_).
  void analyse(const Scene& scene);
  /// One pass over the scene's terms into the current layout, starting from the constant bands
  /// (use_constant) or from zero; false when an entry did not fit.
  bool fill(const Scene& scene, const SceneState& s, double k_factor, double d_factor, bool use_constant);
  /// The constant band of every band block at (k_factor, d_factor); false when an entry did not fit.
  bool fillConstant(const Scene& scene, const SceneState& s, double k_factor, double d_factor);
  static constexpr int kSparse = -1;  // route(): the entry goes to the sparse triplets
  static constexpr int kMisfit = -2;  // route(): the layout cannot hold the entry
  /// Where the entry coupling global points i and j goes: a band block's index, kSparse or kMisfit
  /// (noted: the pass is redone after a new analysis).
  int route(int i, int j);
  /// Lower-triangle add a_rc += value in a band block (local coordinates, r >= c).
  void addLower(Block& block, int r, int c, double value);
  /// Scatters this assembly's triplets into the sparse blocks; factors every block.
  std::string factorBlocks(const Scene& scene);
  /// Rebuilds a sparse block's matrix and slot table from this assembly's triplets.
  void rebuildSparse(Block& block);
  /// Z = B⁻¹ U and the factored capacitance matrix of a band block with rank-one terms.
  std::string factorLowRank(Block& block);
  /// x := A⁻¹ x for a band block (band solve, then the Woodbury correction).
  void solveBand(const Block& block, Eigen::Ref<VecX> x) const;
  /// x := A_block⁻¹ x in the block's own slot order.
  void solveLocal(const Block& block, Eigen::Ref<VecX> x) const;
  /// The block's slot of global group g.
  int slotOf(int g) const { return coupled_ ? g : group_slot_[g]; }

  LinearSolverChoice choice_;
  long revision_ = 0;
  long layouts_ = 0;
  bool coupled_ = false;
  bool fits_ = true;            // every entry of the current pass fitted the layout
  bool constant_pass_ = false;  // fillConstant is running: band adds go to Block::constant
  bool has_constant_ = false;   // constant bands hold M + constant Jacobians at constant_key_
  double constant_key_[2] = {0.0, 0.0};
  std::vector<Block> blocks_;
  std::vector<int> body_block_;   // block of each body
  std::vector<int> point_body_;   // body of each global group (points, then internal triples)
  std::vector<int> group_slot_;   // slot of each global group in its body's block
  int point_count_ = 0;           // N
  int internal_velocity_base_ = 0;  // 3N + E: where the internal DOFs start in a velocity-layout vector
  std::vector<int> body_first_;   // first global point of each body
  std::vector<int> wanted_range_;  // per body: largest |i − j| seen (−1: none yet)
  bool wanted_coupling_ = false;   // an entry coupled two bodies
  Triplets triplets_;              // entries of sparse blocks in this assembly (global coordinates)
  std::vector<Eigen::Triplet<double>> scratch_;  // lower triplets for a sparse rebuild
};

}  // namespace filum::mechanics
