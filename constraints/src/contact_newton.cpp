#include "filum/constraints/contact_newton.hpp"

#include <algorithm>
#include <cmath>

namespace filum::constraints {

namespace {

using Kind = ConstraintRows::Kind;

/// A friction pair starts at row r (its normal row is r − 1).
bool startsFrictionPair(const ConstraintRows& rows, int r) {
  return rows.kind(r) == Kind::kFriction && rows.kind(r - 1) == Kind::kNormal;
}

}  // namespace

void ContactNewton::grow(int c) {
  if (capacity_ >= c) return;  // grows only: a steady step allocates nothing
  capacity_ = 2 * c;
  held_ = false;  // (lu_ is reallocated)
  for (VecX* v : {&rho_, &wl_, &f_, &delta_, &trial_, &best_, &rhs_, &compliance_, &diagonal_, &w_free_, &wl_base_,
                  &w_delta_, &w_lambda_})
    v->resize(capacity_);
  lu_.resize(capacity_, capacity_);
  solved_.reserve(capacity_);
  held_solved_.reserve(capacity_);
  held_pattern_.reserve(capacity_);
  free_.reserve(capacity_);
  pivot_.resize(capacity_);
  is_free_.resize(capacity_);
  forms_.resize(capacity_);
  row_position_.resize(capacity_);
}

void ContactNewton::scale(const Eigen::Ref<const VecX>& diagonal, const ConstraintRows& rows) {
  // ρ_r = 1/W_rr; a friction pair shares 2/(W_t1t1 + W_t2t2) so that its disc stays round. A row
  // with W_rr <= 0 touches no point (W is positive semi-definite): ρ = 0 marks it, λ_r = 0.
  for (int r = 0; r < c_; ++r) {
    if (startsFrictionPair(rows, r)) {
      const double sum = diagonal[r] + diagonal[r + 1];
      rho_[r] = rho_[r + 1] = sum > 0.0 ? 2.0 / sum : 0.0;
      ++r;
      continue;
    }
    rho_[r] = diagonal[r] > 0.0 ? 1.0 / diagonal[r] : 0.0;
  }
}

double ContactNewton::evaluate(bool jacobian, const ConstraintRows& rows, const Eigen::Ref<const VecX>& lambda) {
  const int c = c_;
  // A row whose F is λ_r itself (D = 0): its step is −λ_r, no W in its Jacobian row.
  auto freeRow = [&](int r) {
    f_[r] = lambda[r];
    if (jacobian) is_free_[r] = 1;
  };
  // A row whose F is ρ_r w_r (D = 1): its Jacobian row is ρ_r W_r.
  auto tiedRow = [&](int r) {
    f_[r] = rho_[r] * wl_[r];
    if (!jacobian) return;
    is_free_[r] = 0;
    forms_[r] = NewtonRowForm();
    forms_[r].addW(r, rho_[r]);
    forms_[r].addUnit(r, rho_[r] * compliance_[r]);
  };
  for (int r = 0; r < c; ++r) {
    const Kind kind = rows.kind(r);
    if (!(rho_[r] > 0.0)) {
      freeRow(r);
      continue;
    }
    if (kind == Kind::kEquality) {
      tiedRow(r);
      continue;
    }
    if (kind == Kind::kNormal) {
      // F_n = λ_n − max(0, z_n): ρ_n w_n when z_n > 0, else λ_n.
      const double zn = lambda[r] - rho_[r] * wl_[r];
      if (zn > 0.0)
        tiedRow(r);
      else
        freeRow(r);
      continue;
    }
    // A friction pair (r, r + 1) of the normal row n = r − 1.
    const int n = r - 1, t1 = r, t2 = r + 1;
    const double mu = rows.friction(r);
    const double zn = lambda[n] - rho_[n] * wl_[n];
    const double radius = mu * std::max(0.0, zn);
    const double z1 = lambda[t1] - rho_[t1] * wl_[t1], z2 = lambda[t2] - rho_[t2] * wl_[t2];
    // |z_t| by its square root, not std::hypot (several times slower, guarding an overflow that
    // needs |z| > 1e154 m/s²). Below 1e-154 m/s² z² underflows (to 0 in a step, which flushes
    // subnormals): such a pair sticks, where the exact norm could slide it if μ z_n were smaller
    // still — a force at round-off level either way.
    const double norm = std::sqrt(z1 * z1 + z2 * z2);
    r = t2;
    if (!(radius > 0.0)) {  // no normal force: no friction
      freeRow(t1);
      freeRow(t2);
      continue;
    }
    if (norm <= radius) {  // stick: w_t = 0
      tiedRow(t1);
      tiedRow(t2);
      continue;
    }
    // Slide: P = R ẑ, F_t = λ_t − R ẑ;
    // ∂F_t = E_t − S (E_t − ρ_t W_t) − μ ẑ (e_n − ρ_n W_n),  S = (R/|z_t|)(I − ẑẑᵀ).
    const Eigen::Vector2d hat(z1 / norm, z2 / norm);
    f_[t1] = lambda[t1] - radius * hat[0];
    f_[t2] = lambda[t2] - radius * hat[1];
    if (!jacobian) continue;
    is_free_[t1] = is_free_[t2] = 0;
    const Eigen::Matrix2d s = (radius / norm) * (Eigen::Matrix2d::Identity() - hat * hat.transpose());
    const int t[2] = {t1, t2};
    // Row t_i as a form Σ b_k W_k + Σ c_m e_m: W's rows of t1, t2 and n (with the compliance R
    // of each: J holds W + R) and the unit terms e_ti − S_i· E_t − μ ẑ_i e_n.
    for (int i = 0; i < 2; ++i) {
      NewtonRowForm& form = forms_[t[i]];
      form = NewtonRowForm();
      form.addW(t1, s(i, 0) * rho_[t1]);
      form.addW(t2, s(i, 1) * rho_[t2]);
      form.addW(n, mu * hat[i] * rho_[n]);
      form.addUnit(t1, s(i, 0) * rho_[t1] * compliance_[t1] - s(i, 0));
      form.addUnit(t2, s(i, 1) * rho_[t2] * compliance_[t2] - s(i, 1));
      form.addUnit(n, mu * hat[i] * rho_[n] * compliance_[n] - mu * hat[i]);
      form.addUnit(t[i], 1.0);
    }
  }
  double merit = 0.0;
  max_abs_residual_ = 0.0;
  force_scale_ = 0.0;
  for (int r = 0; r < c; ++r) {
    if (!(rho_[r] > 0.0)) continue;
    const double scaled = f_[r] / rho_[r];  // m/s²
    merit += scaled * scaled;
    max_abs_residual_ = std::max(max_abs_residual_, std::abs(scaled));
    force_scale_ = std::max(force_scale_, std::abs(lambda[r]) / rho_[r]);
  }
  return merit;
}

bool ContactNewton::factor(int s) {
  // Doolittle LU with partial pivoting, in place, right-looking (one rank-1 update per column).
  for (int k = 0; k < s; ++k) {
    int p = k;
    lu_.col(k).segment(k, s - k).cwiseAbs().maxCoeff(&p);
    p += k;
    pivot_[k] = p;
    const double pivot = lu_(p, k);
    if (!(std::abs(pivot) > 0.0) || !std::isfinite(pivot)) return false;
    if (p != k) lu_.row(k).head(s).swap(lu_.row(p).head(s));
    const int m = s - k - 1;
    if (m == 0) continue;
    lu_.col(k).segment(k + 1, m) /= pivot;
    lu_.block(k + 1, k + 1, m, m).noalias() -= lu_.col(k).segment(k + 1, m) * lu_.row(k).segment(k + 1, m);
  }
  return true;
}

void ContactNewton::substitute(int s, Eigen::Ref<VecX> x) const {
  for (int k = 0; k < s; ++k)
    if (pivot_[k] != k) std::swap(x[k], x[pivot_[k]]);
  lu_.topLeftCorner(s, s).triangularView<Eigen::UnitLower>().solveInPlace(x.head(s));
  lu_.topLeftCorner(s, s).triangularView<Eigen::Upper>().solveInPlace(x.head(s));
}

bool ContactNewton::structuredStep(double damping, const ConstraintRows& rows) {
  // Below 64 rows the dense LU (≤ 87 k multiply-adds, ~25 µs) costs about what laying the
  // augmented system out does, whatever its envelope: not tried (knot.json's solves, measured:
  // building without taking it added 6 % to its step time).
  constexpr int kSmallestStructured = 64;
  if (!structured_ || !structure_ || !structure_->inverse || !structure_->problem || !structure_->point_body ||
      static_cast<int>(solved_.size()) < kSmallestStructured)
    return false;
  if (!augmented_.build(rows, solved_, row_position_, forms_, damping, *structure_->inverse, *structure_->problem,
                        *structure_->point_body))
    return false;
  // The dense LU's s³/3 multiply-adds run as long vectorized rank-1 updates (3.4–3.8 G/s on the
  // 2-core machine of the benchmarks, s = 150–600), the envelope LU's as short dot products
  // (1.4–2.2 G/s for envelopes 12–96 wide): measured, a factor 2 between them. With W's products
  // through the band (W deferred: LagrangeMultiplierSolver), the dense step reads W's entries, so
  // its cost counts forming W while this solve has not: about a product through the band per
  // column, c of them (by columns; from A⁻¹'s point blocks it is of the same order, 3 solves per
  // point and 36 multiply-adds per point and row).
  constexpr double kEnvelopeRateRatio = 2.0;
  const double s = static_cast<double>(solved_.size());
  const double forming = product_ && !entries_->formed() ? static_cast<double>(c_) * product_->cost() : 0.0;
  if (kEnvelopeRateRatio * augmented_.cost() >= s * s * s / 3.0 + forming) return false;
  if (!augmented_.factor()) return false;
  // A small pivot (sliding rows, an indefinite A: augmented_newton_system.hpp) shows as a
  // non-finite solution: the dense LU, with its partial pivoting, solves the same system then.
  const int n = static_cast<int>(solved_.size());
  trial_.head(n) = rhs_.head(n);  // (trial_ is free until the line search)
  augmented_.solve(rhs_.head(n));
  if (rhs_.head(n).allFinite()) return true;
  rhs_.head(n) = trial_.head(n);
  return false;
}

void ContactNewton::denseSystem(int s, double damping) {
  // J_SS + δ I from the forms: lu_(i, j) = Σ_k b_k W(k, S_j) + c(r, S_j) + δ_ij.
  const MatX& w = matrix();
  for (int i = 0; i < s; ++i) {
    const NewtonRowForm& form = forms_[solved_[i]];
    for (int j = 0; j < s; ++j) {
      double sum = 0.0;
      for (int k = 0; k < form.nb; ++k) sum += form.b[k] * w(solved_[j], form.bk[k]);  // (W symmetric: down a column)
      lu_(i, j) = sum;
    }
    for (int k = 0; k < form.nc; ++k)
      if (row_position_[form.ck[k]] >= 0) lu_(i, row_position_[form.ck[k]]) += form.c[k];
    lu_(i, i) += damping;
  }
}

bool ContactNewton::heldFits() const {
  if (!held_ || held_solved_.size() != solved_.size()) return false;
  for (std::size_t i = 0; i < solved_.size(); ++i)
    if (held_solved_[i] != solved_[i] || held_pattern_[i] != forms_[solved_[i]].nb) return false;
  return true;
}

void ContactNewton::hold(bool structured) {
  held_ = true;
  held_structured_ = structured;
  held_solved_.assign(solved_.begin(), solved_.end());
  held_pattern_.clear();
  for (int r : solved_) held_pattern_.push_back(forms_[r].nb);
}

bool ContactNewton::step(double damping, const ConstraintRows& rows, bool chord) {
  const int c = c_;
  solved_.clear();
  free_.clear();
  for (int r = 0; r < c; ++r) (is_free_[r] ? free_ : solved_).push_back(r);
  // Free rows: Δ_r = −F_r (= −λ_r).
  for (int r : free_) delta_[r] = -f_[r];
  const int s = static_cast<int>(solved_.size());
  chord_taken_ = step_structured_ = false;
  if (s == 0) return true;
  for (int r = 0; r < c; ++r) row_position_[r] = -1;
  for (int i = 0; i < s; ++i) row_position_[solved_[i]] = i;
  // −F_S − J_SI Δ_I: J_SI Δ_I = Σ_k b_k (W Δ_I)_k + the unit terms on free rows; W Δ_I over the
  // free rows that move (most have λ = 0 and Δ = 0), a column of W each (W is symmetric).
  int moving = 0;
  for (int k : free_)
    if (delta_[k] != 0.0) ++moving;
  // (The columns' axpys run vectorized, as the dense product: the same rate ratio as chooseProduct's;
  // W not formed yet, the band's product spares forming it.)
  if (moving == 0) {
    w_free_.head(c).setZero();  // (no product: the free rows stay at λ = 0)
  } else if (product_ && (w_matrix_ == nullptr ||
                          static_cast<double>(moving) * c > BandDelassusProduct::kDenseProductRateRatio * product_->cost())) {
    // (trial_ is free until the line search.)
    trial_.head(c).setZero();
    for (int k : free_) trial_[k] = delta_[k];
    multiplyW(rows, trial_.head(c), w_free_.head(c));
  } else {
    w_free_.head(c).setZero();
    for (int k : free_)
      if (delta_[k] != 0.0) w_free_.head(c).noalias() += delta_[k] * matrix().col(k).head(c);
  }
  for (int i = 0; i < s; ++i) {
    const NewtonRowForm& form = forms_[solved_[i]];
    double sum = -f_[solved_[i]];
    for (int k = 0; k < form.nb; ++k) sum -= form.b[k] * w_free_[form.bk[k]];
    for (int k = 0; k < form.nc; ++k)
      if (row_position_[form.ck[k]] < 0) sum -= form.c[k] * delta_[form.ck[k]];
    rhs_[i] = sum;
  }
  // (J_SS + δ I) Δ_S = that: on the held factorization (a chord step: header), through A's
  // band, or by a dense LU.
  chord_taken_ = chord && heldFits();
  if (chord_taken_) {
    step_structured_ = held_structured_;
    trial_.head(s) = rhs_.head(s);  // (trial_ is free until the line search)
    if (held_structured_)
      augmented_.solve(rhs_.head(s));
    else
      substitute(s, rhs_.head(s));
    if (!rhs_.head(s).allFinite()) {  // not a factorization to go on with: a fresh one
      chord_taken_ = false;
      rhs_.head(s) = trial_.head(s);
    }
  }
  if (!chord_taken_) {
    held_ = false;  // (the band's layout and lu_ are overwritten below)
    step_structured_ = structuredStep(damping, rows);
    if (step_structured_) {
      hold(true);  // (its solution is finite: structuredStep checked)
    } else {
      denseSystem(s, damping);
      if (!factor(s)) return false;
      substitute(s, rhs_.head(s));
      if (rhs_.head(s).allFinite()) hold(false);
    }
  }
  for (int i = 0; i < s; ++i) delta_[solved_[i]] = rhs_[i];
  return delta_.head(c).allFinite();
}

void ContactNewton::chooseProduct(const ConstraintRows& rows) {
  product_ = nullptr;
  if (!structured_ || !structure_ || c_ == 0) return;
  BandDelassusProduct* product = structure_->product;
  if (product == nullptr) {
    if (!structure_->inverse || !structure_->problem || !structure_->point_body) return;
    product = &own_product_;
    if (!product->prepare(rows, *structure_->inverse, *structure_->problem, *structure_->point_body)) return;
  }
  if (product->cheaperThanDense()) product_ = product;
}

const MatX& ContactNewton::matrix() {
  if (w_matrix_ == nullptr) w_matrix_ = &entries_->matrix();
  return *w_matrix_;
}

void ContactNewton::multiplyW(const ConstraintRows& rows, const Eigen::Ref<const VecX>& x, Eigen::Ref<VecX> out) {
  const int c = c_;
  if (product_) {
    product_->multiply(rows, x, out);
    return;
  }
  out.noalias() = matrix().topLeftCorner(c, c) * x;
}

namespace {

/// W already formed.
class FormedDelassus final : public DelassusEntries {
 public:
  explicit FormedDelassus(const MatX& w) : w_(w) {}
  const MatX& matrix() override { return w_; }
  bool formed() const override { return true; }

 private:
  const MatX& w_;
};

}  // namespace

ContactNewton::Result ContactNewton::solve(const MatX& w, const Eigen::Ref<const VecX>& beta,
                                           const Eigen::Ref<const VecX>& compliance, const ConstraintRows& rows,
                                           const Settings& settings, double tolerance, Eigen::Ref<VecX> lambda,
                                           const Structure* structure) {
  FormedDelassus formed(w);
  const Eigen::Index c = beta.size();
  if (formed_diagonal_.size() < c) formed_diagonal_.resize(2 * c);  // grows only (W's diagonal is strided)
  formed_diagonal_.head(c) = w.diagonal().head(c);
  return solve(formed, formed_diagonal_.head(c), beta, compliance, rows, settings, tolerance, lambda, structure);
}

ContactNewton::Result ContactNewton::solve(DelassusEntries& w, const Eigen::Ref<const VecX>& w_diagonal,
                                           const Eigen::Ref<const VecX>& beta, const Eigen::Ref<const VecX>& compliance,
                                           const ConstraintRows& rows, const Settings& settings, double tolerance,
                                           Eigen::Ref<VecX> lambda, const Structure* structure) {
  const int c = static_cast<int>(beta.size());
  c_ = c;
  entries_ = &w;
  w_matrix_ = nullptr;
  structure_ = structure;
  structured_ = settings.structured;
  grow(c);
  // A factorization is carried over only for the same W and rows (Settings::matrix_key).
  if (settings.matrix_key < 0 || settings.matrix_key != held_key_) held_ = false;
  held_key_ = settings.matrix_key;
  compliance_.head(c) = compliance;
  diagonal_.head(c) = w_diagonal + compliance;
  scale(diagonal_.head(c), rows);
  for (int r = 0; r < c; ++r)
    if (!(rho_[r] > 0.0)) lambda[r] = 0.0;
  chooseProduct(rows);
  if (!product_) matrix();  // (every product through W)
  // F (and with the matrix, J) at x: w_ = W x − β first.
  auto at = [&](const Eigen::Ref<const VecX>& x, bool jacobian) {
    multiplyW(rows, x, wl_.head(c));
    w_lambda_.head(c) = wl_.head(c);
    wl_.head(c) += compliance_.head(c).cwiseProduct(x) - beta;
    return evaluate(jacobian, rows, x);
  };
  // Along a step, (W + R)(λ + αΔ) − β = wl(λ) + α (W + R)Δ: one product with W per iteration, not
  // one per trial of the line search. Updated so, wl_ drifts from the exact product by round-off
  // (a few ε |W||λ| per iteration, far below any tolerance asked); a residual that looks
  // converged is measured again with the exact product before the solve stops on it.
  bool exact = true;  // wl_ is W λ + Rλ − β computed afresh

  // The residual is asked to be small against the largest term it balances: |β|∞ or a row's
  // force as an acceleration, |λ_r| (W_rr + R_r) — the round-off of (W + R)λ − β is of that size.
  const double beta_scale = beta.lpNorm<Eigen::Infinity>();
  auto threshold = [&] { return this->threshold(tolerance, beta_scale); };
  Result result;
  double merit = at(lambda, true);
  double best_merit = merit;
  best_.head(c) = lambda;
  constexpr double kArmijo = 1e-4;  // sufficient decrease (the usual σ of Armijo's rule)
  constexpr int kHalvings = 30;     // α down to 2⁻³⁰: below that the direction is not one of descent
  // Non-monotone Armijo (Grippo, Lampariello & Lucidi 1986): the decrease is asked against the
  // largest merit of the last kMemory iterates, so a full step that crosses a kink of F (a contact
  // opening, a pair starting to slide) and raises θ for one iterate is still taken.
  constexpr int kMemory = 8;
  double history[kMemory];
  for (double& h : history) h = merit;
  // An accepted iterate's merit: into the history, and kept when it is the best so far.
  auto remember = [&](double accepted) {
    history[result.iterations % kMemory] = accepted;
    if (accepted < best_merit) {
      best_merit = accepted;
      best_.head(c) = lambda;
    }
  };
  // A chord step is taken when it divides |F| by 4 at least (θ by 16); else Newton's own step.
  // Newton near the solution contracts quadratically, so a chord that does less says the
  // factorization is stale. Measured (`filum run`, mean ms per simulated ms, 2026-11-28) with
  // 0.1 / 0.25 / 0.5: the rod of bench_rod (100 nodes dragged over a table) 0.54 / 0.57 / 0.52,
  // capstan_sliding.json 0.86 / 0.95 / 0.81 (single runs, 0.25's the median of 3; the machine's
  // noise is ~10 %, so the times do not choose; the solves' fallbacks 5 / 10 / 5 of ~3700 move
  // with the iterates); 0.5 raised knot.json's iterations by a quarter (5979 → 7376) and left a
  // solve unconverged, so 0.25.
  constexpr double kChordContraction = 0.25;
  bool measured = false;  // wl_ and F are λ's own, from an exact product (the loop's exit on convergence)
  while (true) {
    if (max_abs_residual_ <= threshold()) {
      measured = exact;
      if (exact) break;
      merit = at(lambda, true);
      exact = true;
      continue;
    }
    if (result.iterations >= settings.iterations) break;
    ++result.iterations;
    // Levenberg–Marquardt's shift tied to the residual (Yamashita & Fukushima 2001: δ_k ~ |F_k|
    // keeps Newton's local quadratic rate): far from the solution it holds back the steps along
    // the near-null directions of redundant rows, near it the step is Newton's own.
    const double relative = max_abs_residual_ / std::max({beta_scale, force_scale_, 1e-300});
    const double shift = std::clamp(relative, settings.damping, settings.max_damping);
    if (!step(shift, rows, /*chord=*/settings.chords)) break;
    wl_base_.head(c) = wl_.head(c);
    multiplyW(rows, delta_.head(c), w_delta_.head(c));
    w_delta_.head(c) += compliance_.head(c).cwiseProduct(delta_.head(c));
    if (chord_taken_) {
      // A chord step is taken whole when it divides |F| by 1/kChordContraction (no line search:
      // a chord that needs one is not worth keeping), and the factorization stays held.
      trial_.head(c) = lambda + delta_.head(c);
      wl_.head(c) = wl_base_.head(c) + w_delta_.head(c);
      const double chord_merit = evaluate(false, rows, trial_.head(c));
      if (chord_merit <= kChordContraction * kChordContraction * merit) {
        ++result.chord_steps;
        if (step_structured_) ++result.structured_steps;
        lambda = trial_.head(c);
        merit = evaluate(true, rows, lambda);  // wl_ is the trial's
        exact = false;
        remember(merit);
        continue;
      }
      // Discarded: F and J at λ again, and Newton's own step on a fresh factorization.
      held_ = false;
      wl_.head(c) = wl_base_.head(c);
      merit = evaluate(true, rows, lambda);
      if (!step(shift, rows, /*chord=*/false)) break;
      multiplyW(rows, delta_.head(c), w_delta_.head(c));
      w_delta_.head(c) += compliance_.head(c).cwiseProduct(delta_.head(c));
    }
    if (step_structured_) ++result.structured_steps;
    // Armijo: θ(λ + αΔ) <= (1 − 2σα) θ(λ) (θ = |F|², its slope along a Newton step is −2θ).
    double alpha = 1.0;
    bool accepted = false;
    const double reference = *std::max_element(history, history + kMemory);
    for (int k = 0; k <= kHalvings; ++k, alpha *= 0.5) {
      trial_.head(c) = lambda + alpha * delta_.head(c);
      wl_.head(c) = wl_base_.head(c) + alpha * w_delta_.head(c);
      if (evaluate(false, rows, trial_.head(c)) <= reference - 2.0 * kArmijo * alpha * merit) {
        accepted = true;
        break;
      }
    }
    if (!accepted) {
      held_ = false;
      break;
    }
    // Chord steps only in Newton's local phase: after a full step (a cut one says the active set
    // is still moving, where the next step needs its own Jacobian).
    if (alpha < 1.0) held_ = false;
    lambda = trial_.head(c);
    merit = evaluate(true, rows, lambda);  // wl_ is the accepted trial's
    exact = false;
    remember(merit);
    // A short step: the active set is changing under Newton's feet (a contact opens, a pair
    // starts to slide); the caller smooths with a few Gauss–Seidel sweeps and comes back.
    if (alpha < settings.stall_step && max_abs_residual_ > threshold()) {
      result.stalled = true;
      break;
    }
  }
  // The last evaluation may have been a rejected trial: measure the iterate itself (unless the
  // loop stopped on λ's own exact measure: the same product again would give the same bits).
  if (!measured) at(lambda, false);
  result.converged = max_abs_residual_ <= threshold();
  if (!result.converged) {
    lambda = best_.head(c);
    at(lambda, false);
    result.converged = max_abs_residual_ <= threshold();
  }
  structure_ = nullptr;  // (the caller's, valid during this call only)
  entries_ = nullptr;
  w_matrix_ = nullptr;
  product_ = nullptr;
  result.residual = max_abs_residual_;
  result.threshold = threshold();
  return result;
}

double ContactNewton::residual(const ConstraintRows& rows, const Eigen::Ref<const VecX>& diagonal,
                               const Eigen::Ref<const VecX>& wl, const Eigen::Ref<const VecX>& lambda) {
  const int c = static_cast<int>(wl.size());
  c_ = c;
  grow(c);
  scale(diagonal, rows);
  wl_.head(c) = wl;
  evaluate(false, rows, lambda);
  return max_abs_residual_;
}

}  // namespace filum::constraints
