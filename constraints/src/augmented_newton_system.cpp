#include "filum/constraints/augmented_newton_system.hpp"

#include <algorithm>
#include <cassert>
#include <limits>

#include "filum/core/growing_vector.hpp"

namespace filum::constraints {

int AugmentedNewtonSystem::groupOfPoint(int p) const {
  const int body = (*point_body_)[p];
  const int base = body_base_[body];
  if (base < 0) return -1;
  return base + bands_[body].point_group[p - problem_->bodies[body].offset()];
}

int AugmentedNewtonSystem::groupPosition(int rank) const { return 3 * rank + rows_before_[rank]; }

bool AugmentedNewtonSystem::orderGroups(bool merge) {
  const ConstraintRows& rows = *rows_;
  constexpr double kUnkeyed = std::numeric_limits<double>::infinity();
  resizeGrowing(key_, groups_);
  std::fill(key_.begin(), key_.end(), kUnkeyed);
  double next = 0.0;  // a key beyond every key given so far
  for (std::size_t t_index = 0; t_index < touched_.size(); ++t_index) {
    const int body = touched_[t_index], base = body_base_[body], count = bands_[body].groups;
    // Rows between this body and the bodies before it: each of its groups takes the smallest key
    // the row reaches in them.
    if (merge && t_index > 0)
      for (int r : *solved_) {
        double earlier = kUnkeyed;
        for (int t = rows.begin(r); t < rows.end(r); ++t) {
          const int g = groupOfPoint(rows.point(t));
          assert(g >= 0 && "a solved row's points are on touched bodies");
          if (g < base) earlier = std::min(earlier, key_[g]);
        }
        if (earlier == kUnkeyed) continue;
        for (int t = rows.begin(r); t < rows.end(r); ++t) {
          const int g = groupOfPoint(rows.point(t));
          if (g >= base && g < base + count) key_[g] = std::min(key_[g], earlier);
        }
      }
    // The other groups take the key of the nearest keyed group before them along the body (the
    // first keyed one for those before it); a body no row joins to earlier ones comes after them.
    int first_keyed = base;
    while (first_keyed < base + count && key_[first_keyed] == kUnkeyed) ++first_keyed;
    if (first_keyed == base + count) {
      for (int I = 0; I < count; ++I) key_[base + I] = next + I;
    } else {
      for (int g = base; g < base + count; ++g)
        if (key_[g] == kUnkeyed) key_[g] = g < first_keyed ? key_[first_keyed] : key_[g - 1];
    }
    for (int g = base; g < base + count; ++g) next = std::max(next, key_[g] + 1.0);
  }
  // Sorted by key, ties in the bodies' order and along each body (g is both).
  resizeGrowing(by_key_, groups_);
  for (int g = 0; g < groups_; ++g) by_key_[g] = {key_[g], g};
  std::sort(by_key_.begin(), by_key_.end());
  resizeGrowing(rank_, groups_);
  bool moved = false;
  for (int place = 0; place < groups_; ++place) {
    rank_[by_key_[place].second] = place;
    moved = moved || by_key_[place].second != place;
  }
  return moved;
}

bool AugmentedNewtonSystem::build(const ConstraintRows& rows, const std::vector<int>& solved,
                                  const std::vector<int>& row_position, const std::vector<NewtonRowForm>& forms,
                                  double damping, const BlockInverse& inverse, const ConstraintProblem& problem,
                                  const std::vector<int>& point_body) {
  rows_ = &rows;
  solved_ = &solved;
  row_position_ = &row_position;
  forms_ = &forms;
  problem_ = &problem;
  point_body_ = &point_body;
  damping_ = damping;
  const int bodies = static_cast<int>(problem.bodies.size());
  // The bodies the rows act on, each with its band.
  resizeGrowing(body_base_, bodies);
  resizeGrowing(bands_, bodies);
  std::fill(body_base_.begin(), body_base_.end(), -1);
  for (int r : solved)
    for (int t = rows.begin(r); t < rows.end(r); ++t) body_base_[point_body[rows.point(t)]] = 0;
  groups_ = 0;
  touched_.clear();
  for (int b = 0; b < bodies; ++b) {
    if (body_base_[b] < 0) continue;
    if (!inverse.bandBlocks(b, bands_[b])) return false;
    body_base_[b] = groups_;
    groups_ += bands_[b].groups;
    touched_.push_back(b);
  }
  // The merged order where it is cheaper than the bodies one after the other (a single crossing
  // of two threads would pull the whole second one into the middle of the first): both laid out,
  // the cheaper kept.
  const bool merged = orderGroups(true);
  if (!layOut()) return false;
  if (merged) {
    const double merged_cost = lu_.cost();
    merged_rank_.assign(rank_.begin(), rank_.begin() + groups_);  // (capacity kept: no allocation once grown)
    orderGroups(false);
    layOut();
    if (merged_cost < lu_.cost()) {
      std::copy(merged_rank_.begin(), merged_rank_.end(), rank_.begin());
      layOut();
    }
  }
  return true;
}

bool AugmentedNewtonSystem::layOut() {
  const ConstraintRows& rows = *rows_;
  const std::vector<int>& solved = *solved_;
  const std::vector<NewtonRowForm>& forms = *forms_;
  const std::vector<int>& row_position = *row_position_;
  const int s = static_cast<int>(solved.size());
  // Each row after the last group it acts on (through its own terms and those of the rows its
  // form combines, which share its points for contact rows).
  resizeGrowing(by_anchor_, s);
  for (int i = 0; i < s; ++i) {
    const int r = solved[i];
    const NewtonRowForm& form = forms[r];
    int anchor = -1;
    auto reach = [&](int row) {
      for (int t = rows.begin(row); t < rows.end(row); ++t) anchor = std::max(anchor, rankOfPoint(rows.point(t)));
    };
    reach(r);
    for (int j = 0; j < form.nb; ++j) {
      if (row_position[form.bk[j]] < 0) return false;
      reach(form.bk[j]);
    }
    for (int j = 0; j < form.nc; ++j)
      if (row_position[form.ck[j]] < 0) return false;
    if (anchor < 0) return false;  // a row on no point (cannot be solved: ρ = 0 rows are free)
    by_anchor_[i] = {anchor, i};
  }
  std::sort(by_anchor_.begin(), by_anchor_.end());
  resizeGrowing(rows_before_, groups_ + 1);
  resizeGrowing(row_unknown_, s);
  int k = 0;
  for (int g = 0; g <= groups_; ++g) {
    rows_before_[g] = k;
    for (int rank = 0; k < s && by_anchor_[k].first == g; ++k, ++rank) row_unknown_[by_anchor_[k].second] = 3 * (g + 1) + rows_before_[g] + rank;
  }
  const int n = 3 * groups_ + s;
  // The envelope: A's bands, each row's points and the rows its form names.
  lu_.reset(n);
  for (int b : touched_) {
    const BandBlocks& band = bands_[b];
    for (int I = 0; I < band.groups; ++I)
      for (int J = std::max(0, I - band.range); J <= I; ++J) {
        // Block (I, J) and its transpose, wherever the order put the two groups.
        const int pi = groupPosition(rank_[body_base_[b] + I]), pj = groupPosition(rank_[body_base_[b] + J]);
        for (int a = 0; a < 3; ++a) lu_.widen(std::max(pi, pj) + a, std::min(pi, pj));
      }
  }
  for (int i = 0; i < s; ++i) {
    const int r = solved[i], position = row_unknown_[i];
    const NewtonRowForm& form = forms[r];
    for (int t = rows.begin(r); t < rows.end(r); ++t) lu_.widen(position, groupPosition(rankOfPoint(rows.point(t))));
    for (int j = 0; j < form.nb; ++j)
      for (int t = rows.begin(form.bk[j]); t < rows.end(form.bk[j]); ++t)
        lu_.widen(position, groupPosition(rankOfPoint(rows.point(t))));
    for (int j = 0; j < form.nc; ++j) lu_.widen(position, row_unknown_[row_position[form.ck[j]]]);
  }
  if (x_.size() < n) x_.resize(2 * n);  // grows only
  return true;
}

bool AugmentedNewtonSystem::factor(bool positive_pivots) {
  const ConstraintRows& rows = *rows_;
  lu_.allocate();
  // A, both triangles (the band holds the lower one; a diagonal block only its lower triangle).
  for (std::size_t b = 0; b < body_base_.size(); ++b) {
    if (body_base_[b] < 0) continue;
    const BandBlocks& band = bands_[b];
    for (int I = 0; I < band.groups; ++I) {
      const int pi = groupPosition(rank_[body_base_[b] + I]);
      for (int J = std::max(0, I - band.range); J <= I; ++J) {
        const int pj = groupPosition(rank_[body_base_[b] + J]);
        const Eigen::Matrix3d& block = band.block(I, J);
        for (int a = 0; a < 3; ++a)
          for (int c = 0; c < 3; ++c) {
            if (I == J && c > a) continue;
            lu_.at(pi + a, pj + c) = block(a, c);
            if (I != J || a != c) lu_.at(pj + c, pi + a) = block(a, c);
          }
      }
    }
  }
  // The rows: −L_rᵀ in A's rows, Σ b_k L_k and C (and δ) in the row's own.
  for (std::size_t i = 0; i < solved_->size(); ++i) {
    const int r = (*solved_)[i], position = row_unknown_[i];
    const NewtonRowForm& form = (*forms_)[r];
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      const int pg = groupPosition(rankOfPoint(rows.point(t)));
      for (int a = 0; a < 3; ++a) lu_.at(pg + a, position) -= rows.coeff(t)[a];
    }
    for (int j = 0; j < form.nb; ++j)
      for (int t = rows.begin(form.bk[j]); t < rows.end(form.bk[j]); ++t) {
        const int pg = groupPosition(rankOfPoint(rows.point(t)));
        for (int a = 0; a < 3; ++a) lu_.at(position, pg + a) += form.b[j] * rows.coeff(t)[a];
      }
    for (int j = 0; j < form.nc; ++j) lu_.at(position, row_unknown_[(*row_position_)[form.ck[j]]]) += form.c[j];
    lu_.at(position, position) += damping_;
  }
  return lu_.factor(positive_pivots);
}

void AugmentedNewtonSystem::solve(Eigen::Ref<VecX> rhs) {
  const int s = static_cast<int>(solved_->size());
  x_.head(lu_.size()).setZero();
  for (int i = 0; i < s; ++i) x_[row_unknown_[i]] = rhs[i];
  lu_.solve(x_.head(lu_.size()));
  for (int i = 0; i < s; ++i) rhs[i] = x_[row_unknown_[i]];
}

}  // namespace filum::constraints
