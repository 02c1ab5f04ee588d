#include "filum/mechanics/step_matrix.hpp"

#include <algorithm>
#include <cstdlib>

#include "filum/core/scene.hpp"

namespace filum::mechanics {

LinearSolverChoice linearSolverFromParams(const Params& p) {
  const std::string name = p.string("linear_solver", "auto");
  if (name == "auto") return LinearSolverChoice::Auto;
  if (name == "band") return LinearSolverChoice::Band;
  if (name == "sparse") return LinearSolverChoice::Sparse;
  p.fail("linear_solver", "\"auto\", \"band\" or \"sparse\"", "\"" + name + "\"");
}

namespace {
// Half bandwidth of the interleaved 3n × 3n matrix when points up to `range` apart interact.
int halfBandwidth(int range) { return 3 * range + 2; }
}  // namespace

void StepMatrix::analyse(const Scene& scene) {
  const auto& bodies = scene.bodies();
  const int body_count = static_cast<int>(bodies.size());
  const int groups = scene.stepGroupCount();
  const bool new_scene = static_cast<int>(point_body_.size()) != groups || static_cast<int>(body_first_.size()) != body_count;
  if (new_scene) {
    point_body_.assign(groups, 0);
    group_slot_.assign(groups, 0);
    body_first_.assign(body_count, 0);
    wanted_range_.assign(body_count, -1);
    wanted_coupling_ = false;
    for (int b = 0; b < body_count; ++b) {
      const MechanicalState& body = *bodies[b];
      body_first_[b] = body.offset();
      for (int i = 0; i < body.pointCount(); ++i) {
        point_body_[body.offset() + i] = b;
        group_slot_[body.offset() + i] = body.stepSlotOfPoint(i);
      }
      for (int k = 0; k < body.internalVelocityCount() / 3; ++k) {
        point_body_[body.internalGroup(k)] = b;
        group_slot_[body.internalGroup(k)] = body.stepSlotOfInternal(k);
      }
    }
  }
  point_count_ = scene.dofPointCount();
  internal_velocity_base_ = 3 * point_count_ + scene.extraDofCount();
  body_block_.assign(body_count, 0);
  blocks_.clear();
  has_constant_ = false;
  ++layouts_;

  // One sparse block for everything when bodies are coupled, else one block per body whose band
  // is as wide as the body declares (couplingRange) or as the entries turned out to need.
  coupled_ = wanted_coupling_;
  if (coupled_) {
    Block& block = blocks_.emplace_back();
    block.first_point = 0;
    block.points = groups;
    block.point_slots = point_count_;
    block.band = false;
    block.work.resize(3 * groups);
    return;
  }
  for (int b = 0; b < body_count; ++b) {
    const MechanicalState& body = *bodies[b];
    Block& block = blocks_.emplace_back();
    block.first_point = body.offset();
    block.point_slots = body.pointCount();
    block.points = body.pointCount() + body.internalVelocityCount() / 3;
    block.contiguous = block.points == block.point_slots;
    for (int i = 0; i < body.pointCount() && block.contiguous; ++i) block.contiguous = body.stepSlotOfPoint(i) == i;
    if (!block.contiguous) {
      block.group_of_slot.assign(block.points, 0);
      for (int i = 0; i < body.pointCount(); ++i) block.group_of_slot[body.stepSlotOfPoint(i)] = body.offset() + i;
      for (int k = 0; k < body.internalVelocityCount() / 3; ++k)
        block.group_of_slot[body.stepSlotOfInternal(k)] = body.internalGroup(k);
      block.work.resize(3 * block.points);
    }
    const int declared = body.couplingRange();
    block.range = std::max({declared, wanted_range_[b], 0});
    block.band = choice_ == LinearSolverChoice::Band ||
                 (choice_ == LinearSolverChoice::Auto && halfBandwidth(block.range) <= kAutoBandLimit);
    if (block.band) {
      block.band_factor.resize(block.points, block.range);
      block.constant.resize(block.points, block.range);
    }
    body_block_[b] = b;
  }
}

int StepMatrix::route(int i, int j) {
  // kSparse: the entry goes to the triplets of a sparse block; kMisfit: the layout cannot hold it
  // (noted, the pass is redone after a new analysis); else the index of the band block.
  if (coupled_) return kSparse;
  const int bi = point_body_[i], bj = point_body_[j];
  if (bi != bj) {
    wanted_coupling_ = true;
    fits_ = false;
    return kMisfit;
  }
  const int distance = std::abs(group_slot_[i] - group_slot_[j]);
  if (distance > wanted_range_[bi]) wanted_range_[bi] = distance;
  const int b = body_block_[bi];
  const Block& block = blocks_[b];
  if (!block.band) return kSparse;
  if (distance > block.range) {
    fits_ = false;
    return kMisfit;
  }
  return b;
}

void StepMatrix::addLower(Block& block, int r, int c, double value) {
  (constant_pass_ ? block.constant : block.band_factor).addLower(r, c, value);
}

void StepMatrix::addBlock(int i, int j, const Eigen::Matrix3d& value) {
  const int b = route(i, j);
  if (b == kMisfit) return;
  if (b == kSparse) {
    TripletAccumulator(triplets_).addBlock(i, j, value);
    return;
  }
  // Symmetrised: value/2 at (i, j) and valueᵀ/2 at (j, i), of which the lower blocks are kept
  // (a diagonal block's upper triangle is ignored by the factorization).
  Block& block = blocks_[b];
  BlockBandLdlt& target = constant_pass_ ? block.constant : block.band_factor;
  const int I = slotOf(i), J = slotOf(j);
  if (I > J)
    target.block(I, J) += 0.5 * value;
  else if (I < J)
    target.block(J, I) += 0.5 * value.transpose();
  else
    target.block(I, I) += 0.5 * (value + value.transpose());
}

void StepMatrix::addBlockPair(int i, int j, const Eigen::Matrix3d& value) {
  const int b = route(i, j);
  if (b == kMisfit) return;
  if (b == kSparse) {
    TripletAccumulator(triplets_).addBlockPair(i, j, value);
    return;
  }
  // value at (i, j) and valueᵀ at (j, i): symmetric already, the lower one is added.
  Block& block = blocks_[b];
  BlockBandLdlt& target = constant_pass_ ? block.constant : block.band_factor;
  const int I = slotOf(i), J = slotOf(j);
  if (I > J)
    target.block(I, J) += value;
  else
    target.block(J, I) += value.transpose();
}

void StepMatrix::addSupportBlocks(int first, int count, const Eigen::Matrix3d* lower) {
  if (count <= 0) return;
  // The support's two ends decide for all its blocks: points are numbered body by body, so
  // both ends in one band block put every pair in it, at distance <= count − 1.
  const int b = route(first + count - 1, first);
  if (b == kMisfit) return;
  if (b == kSparse || !blocks_[b].contiguous) {  // entry by entry (a body that interleaves slots)
    JacobianAccumulator::addSupportBlocks(first, count, lower);
    return;
  }
  Block& block = blocks_[b];
  BlockBandLdlt& target = constant_pass_ ? block.constant : block.band_factor;
  const int base = first - block.first_point;
  for (int a = 0, k = 0; a < count; ++a)
    for (int c = 0; c <= a; ++c, ++k) target.block(base + a, base + c) += lower[k];  // lower blocks only
}

void StepMatrix::addEntry(int row, int col, double value) {
  const int b = route(row / 3, col / 3);
  if (b == kMisfit) return;
  if (b == kSparse) {
    triplets_.emplace_back(row, col, value);
    return;
  }
  Block& block = blocks_[b];
  const int r = 3 * slotOf(row / 3) + row % 3, c = 3 * slotOf(col / 3) + col % 3;
  addLower(block, std::max(r, c), std::min(r, c), r == c ? value : 0.5 * value);
}

void StepMatrix::addIsotropic(int i, int j, double value) {
  const int b = route(i, j);
  if (b == kMisfit) return;
  if (b == kSparse) {
    TripletAccumulator(triplets_).addIsotropic(i, j, value);
    return;
  }
  Block& block = blocks_[b];
  BlockBandLdlt& target = constant_pass_ ? block.constant : block.band_factor;
  const int I = slotOf(i), J = slotOf(j);
  target.block(std::max(I, J), std::min(I, J)).diagonal().array() += I == J ? value : 0.5 * value;
}

void StepMatrix::addRankOne(int first, ConstPointsRef u, double factor) {
  if (factor == 0.0 || u.rows() == 0) return;
  const int last = first + static_cast<int>(u.rows()) - 1;
  // Only a band block keeps the term apart; elsewhere (sparse, coupled) it is added entry by
  // entry. route() of the two ends checks the term stays in one body.
  const int b = coupled_ ? kSparse : route(first, first);
  if (b == kMisfit) return;
  if (b == kSparse || constant_pass_ || point_body_[first] != point_body_[last] || !blocks_[b].contiguous) {
    JacobianAccumulator::addRankOne(first, u, factor);
    return;
  }
  Block& block = blocks_[b];
  if (block.rank == block.low_rank.cols()) {  // grows on the first assembly only
    block.low_rank.conservativeResize(3 * block.points, block.rank + 1);
    block.sigma.conservativeResize(block.rank + 1);
  }
  auto column = block.low_rank.col(block.rank);
  column.setZero();
  for (Eigen::Index p = 0; p < u.rows(); ++p) column.segment<3>(3 * (first - block.first_point + p)) = u.row(p).transpose();
  block.sigma[block.rank] = factor;
  ++block.rank;
}

bool StepMatrix::fillConstant(const Scene& scene, const SceneState& s, double k_factor, double d_factor) {
  // M ⊗ I₃ and the constant Jacobians, once per step size (docs/architecture.md, "Numbers that
  // matter": assembled once per step size and stored).
  fits_ = true;
  constant_pass_ = true;
  for (Block& block : blocks_) block.constant.setZero();
  scene.addMassMatrix(1.0, *this);
  scene.addForceJacobian(s, k_factor, d_factor, *this, Scene::JacobianTerms::kConstant);
  constant_pass_ = false;
  has_constant_ = fits_;
  constant_key_[0] = k_factor;
  constant_key_[1] = d_factor;
  return fits_;
}

bool StepMatrix::fill(const Scene& scene, const SceneState& s, double k_factor, double d_factor, bool use_constant) {
  fits_ = true;
  triplets_.clear();
  for (Block& block : blocks_) {
    block.rank = 0;
    if (!block.band) continue;
    if (use_constant)
      block.band_factor.assign(block.constant);
    else
      block.band_factor.setZero();
  }
  if (use_constant) {
    scene.addForceJacobian(s, k_factor, d_factor, *this, Scene::JacobianTerms::kVarying);
  } else {
    scene.addMassMatrix(1.0, *this);
    scene.addForceJacobian(s, k_factor, d_factor, *this, Scene::JacobianTerms::kAll);
  }
  return fits_;
}

bool StepMatrix::laidOutFor(const Scene& scene) const {
  return static_cast<int>(point_body_.size()) == scene.stepGroupCount() && point_count_ == scene.dofPointCount() &&
         body_first_.size() == scene.bodies().size() && !blocks_.empty();
}

std::string StepMatrix::assemble(const Scene& scene, const SceneState& s, double k_factor, double d_factor) {
  ++revision_;
  if (!laidOutFor(scene)) {
    point_body_.clear();  // a new scene: forget what earlier assemblies needed
    analyse(scene);
  }
  // At most three passes: the first assembly may find a wider band, then a coupling.
  bool fitted = false;
  for (int pass = 0; pass < 3 && !fitted; ++pass) {
    const bool all_band = std::all_of(blocks_.begin(), blocks_.end(), [](const Block& b) { return b.band; });
    const bool key_changed = constant_key_[0] != k_factor || constant_key_[1] != d_factor;
    fitted = true;
    if (all_band && (!has_constant_ || key_changed)) fitted = fillConstant(scene, s, k_factor, d_factor);
    if (fitted) fitted = fill(scene, s, k_factor, d_factor, all_band);
    if (!fitted) analyse(scene);
  }
  if (!fitted) return "step matrix M - theta h D - kappa h^2 K: its entries did not fit any layout";
  return factorBlocks(scene);
}

std::string StepMatrix::factorBlocks(const Scene& scene) {
  // Sparse blocks: check the pattern is the one analysed and add each entry into the slot found
  // then; a new pattern rebuilds the block (symbolic analysis again).
  for (Block& block : blocks_) {
    if (block.band) continue;
    if (block.lower.nonZeros() > 0) std::fill_n(block.lower.valuePtr(), block.lower.nonZeros(), 0.0);
    block.routed = 0;
    block.pattern_ok = !block.keys.empty();
  }
  for (const Triplet& t : triplets_) {
    Block& block = blocks_[coupled_ ? 0 : body_block_[point_body_[t.row() / 3]]];
    if (!block.pattern_ok) continue;
    const int i = 3 * slotOf(t.row() / 3) + t.row() % 3, j = 3 * slotOf(t.col() / 3) + t.col() % 3;
    const int r = std::max(i, j), c = std::min(i, j);
    const std::size_t k = block.routed++;
    if (k >= block.keys.size() || block.keys[k] != static_cast<long long>(c) * 3 * block.points + r) {
      block.pattern_ok = false;
      continue;
    }
    block.lower.valuePtr()[block.slots[k]] += i == j ? t.value() : 0.5 * t.value();
  }

  for (Block& block : blocks_) {
    std::string failure;
    if (block.band) {
      // Kept for bandBlocks (a structured constraint solve factors A with the rows): O(n r) copies.
      if (block.band_matrix.points() != block.band_factor.points() || block.band_matrix.range() != block.band_factor.range())
        block.band_matrix.resize(block.band_factor.points(), block.band_factor.range());
      block.band_matrix.assign(block.band_factor);
      failure = block.band_factor.factor();
      if (failure.empty() && block.rank > 0) failure = factorLowRank(block);
    } else {
      const bool rebuild = !block.pattern_ok || block.routed != block.keys.size();
      if (rebuild) rebuildSparse(block);
      failure = block.sparse.factor(block.lower, rebuild);
    }
    if (!failure.empty()) {
      // Which body: the block's own, or all of them when a force couples the bodies.
      const std::string of = coupled_ ? "of the coupled bodies"
                                      : "of " + scene.bodies()[point_body_[block.first_point]]->describe();  // a point of the body
      return "step matrix M - theta h D - kappa h^2 K " + of + ": " + failure;
    }
  }
  return "";
}

void StepMatrix::rebuildSparse(Block& block) {
  // Lower triangle of (A + Aᵀ)/2: an off-diagonal entry a_ij contributes a_ij / 2 at (max, min).
  scratch_.clear();
  block.keys.clear();
  const int index = static_cast<int>(&block - blocks_.data());
  const int size = 3 * block.points;
  for (const Triplet& t : triplets_) {
    if ((coupled_ ? 0 : body_block_[point_body_[t.row() / 3]]) != index) continue;
    const int i = 3 * slotOf(t.row() / 3) + t.row() % 3, j = 3 * slotOf(t.col() / 3) + t.col() % 3;
    const int r = std::max(i, j), c = std::min(i, j);
    scratch_.emplace_back(r, c, i == j ? t.value() : 0.5 * t.value());
    block.keys.push_back(static_cast<long long>(c) * size + r);
  }
  block.lower.resize(size, size);
  block.lower.setFromTriplets(scratch_.begin(), scratch_.end());
  block.lower.makeCompressed();
  // Where each triplet's value lands, so that later assemblies scatter without allocating.
  block.slots.resize(block.keys.size());
  const int* outer = block.lower.outerIndexPtr();
  const int* inner = block.lower.innerIndexPtr();
  for (std::size_t k = 0; k < block.keys.size(); ++k) {
    const int c = static_cast<int>(block.keys[k] / size), r = static_cast<int>(block.keys[k] % size);
    block.slots[k] = static_cast<int>(std::lower_bound(inner + outer[c], inner + outer[c + 1], r) - inner);
  }
  block.routed = block.keys.size();
  block.pattern_ok = true;
}

std::string StepMatrix::factorLowRank(Block& block) {
  // Woodbury: Z = B⁻¹ U, C = Σ⁻¹ + Uᵀ Z (rank × rank), factored.
  const int k = block.rank;
  block.solved_low_rank.resize(3 * block.points, k);  // same size from the second assembly on
  block.capacitance.resize(k, k);
  block.projection.resize(k);
  block.correction.resize(k);
  for (int a = 0; a < k; ++a) {
    block.solved_low_rank.col(a) = block.low_rank.col(a);
    block.band_factor.solve(block.solved_low_rank.col(a));
  }
  for (int a = 0; a < k; ++a)
    for (int b = 0; b < k; ++b) block.capacitance(a, b) = block.low_rank.col(a).dot(block.solved_low_rank.col(b));
  for (int a = 0; a < k; ++a) block.capacitance(a, a) += 1.0 / block.sigma[a];
  block.capacitance_factor.compute(block.capacitance);
  const auto& d = block.capacitance_factor.vectorD();
  if (block.capacitance_factor.info() != Eigen::Success || !d.allFinite() || (d.array() == 0.0).any())
    return "the rank-one part of a global energy makes the step matrix singular (Sherman-Morrison)";
  return "";
}

void StepMatrix::solveBand(const Block& block, Eigen::Ref<VecX> x) const {
  // y = B⁻¹ x, then x = y − Z C⁻¹ Uᵀ y (Sherman–Morrison–Woodbury).
  block.band_factor.solve(x);
  if (block.rank == 0) return;
  for (int a = 0; a < block.rank; ++a) block.projection[a] = block.low_rank.col(a).dot(x);
  block.correction = block.capacitance_factor.solve(block.projection);
  for (int a = 0; a < block.rank; ++a) x -= block.correction[a] * block.solved_low_rank.col(a);
}

void StepMatrix::solveLocal(const Block& block, Eigen::Ref<VecX> x) const {
  if (block.band)
    solveBand(block, x);
  else
    block.sparse.solve(x);
}

void StepMatrix::solveBlock(int body, Eigen::Ref<VecX> x) const {
  const Block& block = blocks_[body_block_[body]];
  if (block.contiguous) {
    solveLocal(block, x);
    return;
  }
  // Points at their slots, zero force on the internal DOFs; the points' part back.
  block.work.setZero();
  for (int k = 0; k < block.points; ++k)
    if (const int g = block.group_of_slot[k]; g < point_count_) block.work.segment<3>(3 * k) = x.segment<3>(3 * (g - block.first_point));
  solveLocal(block, block.work);
  for (int k = 0; k < block.points; ++k)
    if (const int g = block.group_of_slot[k]; g < point_count_) x.segment<3>(3 * (g - block.first_point)) = block.work.segment<3>(3 * k);
}

void StepMatrix::solveBlockColumns(int body, Eigen::Ref<MatX> x, int first_point) const {
  const Block& block = blocks_[body_block_[body]];
  if (block.contiguous && block.band && block.rank == 0) {
    block.band_factor.solveColumns(x, first_point);
    return;
  }
  for (Eigen::Index k = 0; k < x.cols(); ++k) solveBlock(body, x.col(k));
}

void StepMatrix::solveAll(Eigen::Ref<VecX> x) const {
  const bool points_only = x.size() == 3 * Eigen::Index(point_count_) && point_body_.size() > std::size_t(point_count_);
  for (const Block& block : blocks_) {
    const bool gather = !block.contiguous || (coupled_ && points_only);
    if (!gather) {
      solveLocal(block, x.segment(3 * block.first_point, 3 * block.points));
      continue;
    }
    const auto group = [&](int k) { return block.contiguous ? block.first_point + k : block.group_of_slot[k]; };
    block.work.setZero();
    for (int k = 0; k < block.points; ++k)
      if (const int g = group(k); !points_only || g < point_count_) block.work.segment<3>(3 * k) = x.segment<3>(3 * g);
    solveLocal(block, block.work);
    for (int k = 0; k < block.points; ++k)
      if (const int g = group(k); !points_only || g < point_count_) x.segment<3>(3 * g) = block.work.segment<3>(3 * k);
  }
}

void StepMatrix::addInternalResponse(Eigen::Ref<const VecX> point_forces, VecX& a) const {
  for (const Block& block : blocks_) {
    if (block.points == block.point_slots) continue;  // no internal DOFs in this block
    const auto group = [&](int k) { return block.contiguous ? block.first_point + k : block.group_of_slot[k]; };
    block.work.setZero();
    for (int k = 0; k < block.points; ++k)
      if (const int g = group(k); g < point_count_) block.work.segment<3>(3 * k) = point_forces.segment<3>(3 * g);
    solveLocal(block, block.work);
    for (int k = 0; k < block.points; ++k)
      if (const int g = group(k); g >= point_count_)
        a.segment<3>(internal_velocity_base_ + 3 * (g - point_count_)) += block.work.segment<3>(3 * k);
  }
}

MatX StepMatrix::assembledMatrix() const {
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(point_body_.size());
  MatX A = MatX::Zero(n, n);
  for (const Block& block : blocks_) {
    const int size = 3 * block.points;
    MatX part(size, size);
    if (block.band) {
      part = block.band_factor.reconstruct();
      for (int k = 0; k < block.rank; ++k) part += block.sigma[k] * block.low_rank.col(k) * block.low_rank.col(k).transpose();
    } else {
      const MatX lower = MatX(block.lower);
      part = lower + lower.transpose();
      part.diagonal() = lower.diagonal();
    }
    const auto group = [&](int k) { return block.contiguous ? block.first_point + k : block.group_of_slot[k]; };
    for (int r = 0; r < block.points; ++r)
      for (int c = 0; c < block.points; ++c) A.block<3, 3>(3 * group(r), 3 * group(c)) = part.block<3, 3>(3 * r, 3 * c);
  }
  return A;
}

std::string StepMatrix::method() const {
  if (blocks_.empty()) return "none (not assembled)";
  std::string out;
  for (const Block& block : blocks_) {
    std::string one = block.band ? "band (half bandwidth " + std::to_string(block.band_factor.halfBandwidth()) + ")"
                                 : block.sparse.method();
    if (block.band && block.rank > 0) one += " + rank " + std::to_string(block.rank) + " (Sherman-Morrison-Woodbury)";
    if (out.find(one) == std::string::npos) out += (out.empty() ? "" : ", ") + one;
  }
  return coupled_ ? "coupled bodies, " + out : out;
}

bool StepMatrix::inverseBandBlocks(int body, int range, std::vector<Eigen::Matrix3d>& out) const {
  BandBlocks band;
  if (!bandBlocks(body, band)) return false;  // (held as a band: the same conditions)
  blocks_[body_block_[body]].band_factor.inverseBand(out, range);
  return true;
}

bool StepMatrix::bandBlocks(int body, BandBlocks& out) const {
  if (coupled_ || body < 0 || body >= static_cast<int>(body_block_.size())) return false;
  const Block& block = blocks_[body_block_[body]];
  if (!block.band || block.rank > 0 || block.band_matrix.points() != block.points) return false;
  out.groups = block.band_matrix.points();
  out.range = block.band_matrix.range();
  out.lower = block.band_matrix.blocks();
  out.point_group = group_slot_.data() + body_first_[body];
  return true;
}

}  // namespace filum::mechanics
