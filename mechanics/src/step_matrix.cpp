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

void StepMatrix::analyse(const Scene& scene, const Triplets& triplets) {
  const auto& bodies = scene.bodies();
  const int body_count = static_cast<int>(bodies.size());
  const int coordinates = 3 * scene.dofPointCount();
  coordinate_body_.assign(coordinates, 0);
  for (int b = 0; b < body_count; ++b)
    std::fill_n(coordinate_body_.begin() + 3 * bodies[b]->offset(), 3 * bodies[b]->pointCount(), b);
  body_block_.assign(body_count, -1);

  // Half bandwidth of each body's block, and whether any entry couples two bodies.
  wanted_width_.assign(body_count, 0);
  bool coupled = false;
  for (const Triplet& t : triplets) {
    const int bi = coordinate_body_[t.row()], bj = coordinate_body_[t.col()];
    if (bi != bj) {
      coupled = true;
      continue;
    }
    wanted_width_[bi] = std::max(wanted_width_[bi], std::abs(t.row() - t.col()));
  }

  // One sparse block for everything when bodies are coupled, else one block per body.
  coupled_ = coupled;
  blocks_.clear();
  if (coupled_) {
    Block& block = blocks_.emplace_back();
    block.first = 0;
    block.size = coordinates;
    block.band = false;
    std::fill(body_block_.begin(), body_block_.end(), 0);
  } else {
    for (int b = 0; b < body_count; ++b) {
      Block& block = blocks_.emplace_back();
      block.first = 3 * bodies[b]->offset();
      block.size = 3 * bodies[b]->pointCount();
      block.band = choice_ == LinearSolverChoice::Band ||
                   (choice_ == LinearSolverChoice::Auto && wanted_width_[b] <= kAutoBandLimit);
      block.half_bandwidth = wanted_width_[b];
      if (block.band) block.band_factor.resize(block.size, block.half_bandwidth);
      body_block_[b] = b;
    }
  }
}

bool StepMatrix::scatter(const Triplets& triplets) {
  for (Block& block : blocks_) {
    if (block.band)
      block.band_factor.setZero();
    else if (block.lower.nonZeros() > 0)
      std::fill_n(block.lower.valuePtr(), block.lower.nonZeros(), 0.0);
    block.routed = 0;
    block.pattern_ok = !block.keys.empty();
  }
  // Band blocks add into the band; sparse blocks check that the pattern is the one analysed and
  // add into the slot found then. A triplet the layout cannot hold (another body's block, out of
  // the band) means the layout must be analysed again: false.
  const bool single = blocks_.size() == 1;
  for (const Triplet& t : triplets) {
    const int index = single ? 0 : body_block_[coordinate_body_[t.row()]];
    if (!single && body_block_[coordinate_body_[t.col()]] != index) return false;
    Block& block = blocks_[index];
    const int i = t.row() - block.first, j = t.col() - block.first;
    const int r = std::max(i, j), c = std::min(i, j);
    const double value = i == j ? t.value() : 0.5 * t.value();
    if (block.band) {
      if (r - c > block.half_bandwidth) return false;
      block.band_factor.addLower(r, c, value);
      continue;
    }
    if (!block.pattern_ok) continue;
    const std::size_t k = block.routed++;
    if (k >= block.keys.size() || block.keys[k] != static_cast<long long>(c) * block.size + r) {
      block.pattern_ok = false;
      continue;
    }
    block.lower.valuePtr()[block.slots[k]] += value;
  }
  return true;
}

void StepMatrix::rebuildSparse(Block& block, const Triplets& triplets) {
  // Lower triangle of (A + Aᵀ)/2: an off-diagonal entry a_ij contributes a_ij / 2 at (max, min).
  scratch_.clear();
  block.keys.clear();
  const int index = static_cast<int>(&block - blocks_.data());
  for (const Triplet& t : triplets) {
    if (body_block_[coordinate_body_[t.row()]] != index) continue;
    const int i = t.row() - block.first, j = t.col() - block.first;
    const int r = std::max(i, j), c = std::min(i, j);
    scratch_.emplace_back(r, c, i == j ? t.value() : 0.5 * t.value());
    block.keys.push_back(static_cast<long long>(c) * block.size + r);
  }
  block.lower.resize(block.size, block.size);
  block.lower.setFromTriplets(scratch_.begin(), scratch_.end());
  block.lower.makeCompressed();
  // Where each triplet's value lands, so that later assemblies scatter without allocating.
  block.slots.resize(block.keys.size());
  const int* outer = block.lower.outerIndexPtr();
  const int* inner = block.lower.innerIndexPtr();
  for (std::size_t k = 0; k < block.keys.size(); ++k) {
    const int c = static_cast<int>(block.keys[k] / block.size), r = static_cast<int>(block.keys[k] % block.size);
    block.slots[k] = static_cast<int>(std::lower_bound(inner + outer[c], inner + outer[c + 1], r) - inner);
  }
}

std::string StepMatrix::assemble(const Scene& scene, const Triplets& triplets) {
  ++revision_;
  // The layout (blocks, band widths) of the previous assembly is tried first; it is analysed
  // again only on the first assembly, when the scene's size changed, or when a triplet does not
  // fit it (e.g. a wider band, or a force now coupling two bodies).
  const bool same_scene = static_cast<int>(coordinate_body_.size()) == 3 * scene.dofPointCount() &&
                          body_block_.size() == scene.bodies().size() && !blocks_.empty();
  if (!same_scene || !scatter(triplets)) {
    analyse(scene, triplets);
    scatter(triplets);  // fits by construction
  }

  for (Block& block : blocks_) {
    std::string failure;
    if (block.band) {
      failure = block.band_factor.factor();
    } else {
      const bool rebuild = !block.pattern_ok || block.routed != block.keys.size();
      if (rebuild) rebuildSparse(block, triplets);
      failure = block.sparse.factor(block.lower, rebuild);
    }
    if (!failure.empty()) return "step matrix M - theta h D - kappa h^2 K: " + failure;
  }
  return "";
}

void StepMatrix::solveBlock(int body, Eigen::Ref<VecX> x) const {
  const Block& block = blocks_[body_block_[body]];
  if (block.band)
    block.band_factor.solve(x);
  else
    block.sparse.solve(x);
}

void StepMatrix::solveAll(Eigen::Ref<VecX> x) const {
  for (const Block& block : blocks_) {
    auto segment = x.segment(block.first, block.size);
    if (block.band)
      block.band_factor.solve(segment);
    else
      block.sparse.solve(segment);
  }
}

std::string StepMatrix::method() const {
  if (blocks_.empty()) return "none (not assembled)";
  std::string out;
  for (const Block& block : blocks_) {
    const std::string one = block.band ? "band (half bandwidth " + std::to_string(block.half_bandwidth) + ")"
                                       : block.sparse.method();
    if (out.find(one) == std::string::npos) out += (out.empty() ? "" : ", ") + one;
  }
  return coupled_ ? "coupled bodies, " + out : out;
}

}  // namespace filum::mechanics
