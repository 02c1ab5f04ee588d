#include "filum/collision/unilateral_contact_solver.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include "filum/core/scene.hpp"

namespace filum::collision {

namespace {

/// Two unit tangents completing n to an orthonormal frame.
void tangents(const Vec3& n, Vec3& t1, Vec3& t2) {
  Eigen::Index axis = 0;
  n.cwiseAbs().minCoeff(&axis);
  t1 = n.cross(Vec3::Unit(axis)).normalized();
  t2 = n.cross(t1);
}

}  // namespace

void UnilateralContactSolver::buildRows(const SceneState& s, const ConstraintRows& bilateral,
                                        const ContactSet& contacts, const Settings& settings) {
  rows_.clear();
  kind_.clear();
  contact_of_row_.clear();
  direction_.clear();
  mu_.clear();
  normal_row_.clear();
  // Bilateral rows first, as the scene built them (L a = E).
  // (Copied term by term, so factored again per axis: anchors that several rows share in the
  // scene's rows get one solve per row here, a few scalar solves that do not matter.)
  for (int r = 0; r < bilateral.rows(); ++r) {
    for (int t = bilateral.begin(r); t < bilateral.end(r); ++t) rows_.addTerm(bilateral.point(t), bilateral.coeff(t));
    rows_.endRow(bilateral.rhs(r));
    kind_.push_back(RowKind::kBilateral);
    contact_of_row_.push_back(-1);
    direction_.push_back(Vec3::Zero());
    mu_.push_back(0.0);
  }
  // Contact rows: e·(a_A − a_B) against rhs, e = n (normal) or t1, t2 (friction), all three on
  // one anchor (+w on A's points, −w on B's).
  auto addRow = [&](int index, const Vec3& e, double rhs, RowKind kind, double mu) {
    rows_.addAnchoredRow(e, rhs);
    kind_.push_back(kind);
    contact_of_row_.push_back(index);
    direction_.push_back(e);
    mu_.push_back(mu);
  };
  const double w = settings.stabilization, wf = settings.friction_rate;
  for (int i = 0; i < static_cast<int>(contacts.size()); ++i) {
    const Contact& c = contacts[i];
    const ContactKinematics k = contactKinematics(c, s);
    rows_.beginAnchor();
    for (int j = 0; j < c.a.count; ++j) rows_.addAnchorPoint(c.offset_a + c.a.point[j], c.a.weight[j]);
    if (!c.againstObstacle())
      for (int j = 0; j < c.b.count; ++j) rows_.addAnchorPoint(c.offset_b + c.b.point[j], -c.b.weight[j]);
    // g̈ >= −2ω ġ − ω² g (the obstacle surface moves at constant velocity over the step).
    normal_row_.push_back(rows_.rows());
    addRow(i, c.normal, -2.0 * w * k.gap_rate - w * w * k.gap, RowKind::kNormal, 0.0);
    if (c.friction > 0.0) {
      // t_j·(a_A − a_B) = −ω_f t_j·(v_A − v_B)
      Vec3 t1, t2;
      tangents(c.normal, t1, t2);
      const Vec3 v = k.v_a - k.v_b;
      addRow(i, t1, -wf * t1.dot(v), RowKind::kFriction, c.friction);
      addRow(i, t2, -wf * t2.dot(v), RowKind::kFriction, c.friction);
    }
  }
}

void UnilateralContactSolver::solveRowColumns(const Scene& scene, const BlockInverse& inverse) {
  const int c = rows_.rows();
  const int points = scene.dofPointCount();
  const auto& bodies = scene.bodies();
  // Columns: the bodies each row touches (the whole scene when the inverse couples them).
  column_start_.assign(1, 0);
  columns_.clear();
  int size = 0;
  for (int r = 0; r < c; ++r) {
    if (inverse.coupled()) {
      columns_.push_back({r, -1, size});
      size += 3 * points;
    } else {
      for (int t = rows_.begin(r); t < rows_.end(r); ++t) {
        const int b = term_body_[t];
        bool known = false;
        for (int g = column_start_[r]; g < static_cast<int>(columns_.size()) && !known; ++g) known = columns_[g].body == b;
        if (!known) {
          columns_.push_back({r, b, size});
          size += 3 * bodies[b]->pointCount();
        }
      }
    }
    column_start_.push_back(static_cast<int>(columns_.size()));
  }
  if (y_.size() < size) y_.resize(2 * size);
  // y_r = A⁻¹ J_rᵀ on each body: scatter the row's coefficients, solve.
  for (const Column& col : columns_) {
    const int offset = col.body < 0 ? 0 : bodies[col.body]->offset();
    const int length = col.body < 0 ? 3 * points : 3 * bodies[col.body]->pointCount();
    auto y = y_.segment(col.start, length);
    y.setZero();
    for (int t = rows_.begin(col.owner); t < rows_.end(col.owner); ++t)
      if (col.body < 0 || term_body_[t] == col.body) y.segment<3>(3 * (rows_.point(t) - offset)) += rows_.coeff(t);
    if (col.body < 0)
      inverse.solveAll(y);
    else
      inverse.solveBlock(col.body, y);
  }
}

void UnilateralContactSolver::solveAnchorColumns(const Scene& scene, const BlockInverse& inverse) {
  const int anchors = rows_.anchors();
  const auto& bodies = scene.bodies();
  // Columns: the bodies each anchor touches, n_b values each.
  column_start_.assign(1, 0);
  columns_.clear();
  int size = 0;
  for (int a = 0; a < anchors; ++a) {
    for (int k = rows_.anchorBegin(a); k < rows_.anchorEnd(a); ++k) {
      const int b = scene.bodyOfPoint(rows_.anchorPoint(k));
      bool known = false;
      for (int g = column_start_[a]; g < static_cast<int>(columns_.size()) && !known; ++g) known = columns_[g].body == b;
      if (!known) {
        columns_.push_back({a, b, size});
        size += bodies[b]->pointCount();
      }
    }
    column_start_.push_back(static_cast<int>(columns_.size()));
  }
  if (y_.size() < size) y_.resize(2 * size);
  // Columns grouped by body (counting sort), three to one 3-column band solve:
  //   z_a = M_b⁻¹ w_a in the x, y or z column of the right-hand side.
  const int body_count = static_cast<int>(bodies.size());
  std::vector<int>& start = term_body_;  // reused as the counting-sort offsets
  start.assign(body_count + 1, 0);
  for (const Column& col : columns_) ++start[col.body + 1];
  for (int b = 0; b < body_count; ++b) start[b + 1] += start[b];
  by_body_.resize(columns_.size());
  for (int g = 0; g < static_cast<int>(columns_.size()); ++g) by_body_[start[columns_[g].body]++] = g;
  int largest = 0;
  for (const MechanicalState* body : bodies) largest = std::max(largest, body->pointCount());
  if (work_.size() < 3 * largest) work_.resize(3 * largest);
  int first = 0;
  for (int b = 0; b < body_count; ++b) {
    const int last = start[b];  // columns of body b: by_body_[first .. last)
    const int n = bodies[b]->pointCount(), offset = bodies[b]->offset();
    for (int chunk = first; chunk < last; chunk += 3) {
      auto work = work_.head(3 * n);
      work.setZero();
      const int width = std::min(3, last - chunk);
      for (int axis = 0; axis < width; ++axis) {
        const Column& col = columns_[by_body_[chunk + axis]];
        for (int k = rows_.anchorBegin(col.owner); k < rows_.anchorEnd(col.owner); ++k) {
          const int p = rows_.anchorPoint(k);
          if (p >= offset && p < offset + n) work[3 * (p - offset) + axis] += rows_.anchorWeight(k);
        }
      }
      inverse.solveBlock(b, work);
      for (int axis = 0; axis < width; ++axis) {
        const Column& col = columns_[by_body_[chunk + axis]];
        for (int i = 0; i < n; ++i) y_[col.start + i] = work[3 * i + axis];
      }
    }
    first = last;
  }
}

int UnilateralContactSolver::columnStart(int owner, int b) const {
  for (int g = column_start_[owner]; g < column_start_[owner + 1]; ++g) {
    if (columns_[g].body < 0) return -2 - columns_[g].start;  // whole-scene column (general path)
    if (columns_[g].body == b) return columns_[g].start;
  }
  return -1;
}

double UnilateralContactSolver::delassus(const Scene& scene, int r, int k) const {
  // W_rk = J_r · y_k, y_k at point p: general path the 3 values of the row column there,
  // factored path Σ_f z_{a_f}(p) e_f over the factors of row k.
  double w = 0.0;
  for (int t = rows_.begin(r); t < rows_.end(r); ++t) {
    const int p = rows_.point(t), b = term_body_[t];
    const int offset = scene.bodies()[b]->offset();
    if (!factored_) {
      const int start = columnStart(k, b);
      if (start >= 0)
        w += rows_.coeff(t).dot(y_.segment<3>(start + 3 * (p - offset)));
      else if (start <= -2)
        w += rows_.coeff(t).dot(y_.segment<3>(-2 - start + 3 * p));
    } else {
      for (int f = rows_.factorBegin(k); f < rows_.factorEnd(k); ++f) {
        const int start = columnStart(rows_.factorAnchor(f), b);
        if (start >= 0) w += y_[start + p - offset] * rows_.coeff(t).dot(rows_.factorDirection(f));
      }
    }
  }
  return w;
}

void UnilateralContactSolver::addColumn(const Scene& scene, int r, double delta, VecX& a) const {
  const auto& bodies = scene.bodies();
  if (!factored_) {
    for (int g = column_start_[r]; g < column_start_[r + 1]; ++g) {
      const Column& col = columns_[g];
      const int offset = col.body < 0 ? 0 : bodies[col.body]->offset();
      const int length = col.body < 0 ? 3 * scene.dofPointCount() : 3 * bodies[col.body]->pointCount();
      a.segment(3 * offset, length) += delta * y_.segment(col.start, length);
    }
    return;
  }
  // a += Δλ Σ_f z_{a_f} ⊗ e_f
  for (int f = rows_.factorBegin(r); f < rows_.factorEnd(r); ++f) {
    const int anchor = rows_.factorAnchor(f);
    const Vec3 e = delta * rows_.factorDirection(f);
    for (int g = column_start_[anchor]; g < column_start_[anchor + 1]; ++g) {
      const Column& col = columns_[g];
      const int offset = bodies[col.body]->offset(), n = bodies[col.body]->pointCount();
      for (int i = 0; i < n; ++i) a.segment<3>(3 * (offset + i)) += y_[col.start + i] * e;
    }
  }
}

void UnilateralContactSolver::iterate(const Scene& scene, const Settings& settings, VecX& a) {
  const int c = rows_.rows();
  int nb = 0;
  while (nb < c && kind_[nb] == RowKind::kBilateral) ++nb;
  stats_.bilateral = nb;
  // Scale of the problem: the largest residual of the unconstrained accelerations, |β|∞.
  auto residual = [&](int r) { return rows_.rhs(r) - rows_.dot(r, a); };
  double scale = 0.0;
  for (int r = 0; r < c; ++r) scale = std::max(scale, std::abs(residual(r)));
  const double threshold = settings.tolerance * std::max(scale, 1e-300);
  // Warm start (the previous stage of the same step): a = a_t + Σ y_r λ_r.
  if (warm_rows_ != c) {
    lambda_.assign(c, 0.0);
  } else {
    for (int r = 0; r < c; ++r)
      if (lambda_[r] != 0.0) addColumn(scene, r, lambda_[r], a);
  }
  warm_rows_ = c;

  // W_rr, and the bilateral block W_BB factored once per stage.
  diagonal_.resize(c);  // std::vector: capacity kept from stage to stage
  for (int r = 0; r < c; ++r) diagonal_[r] = delassus(scene, r, r);
  // W_{t2,t1} of every friction pair (0 on the factored path: one anchor, orthogonal directions).
  coupling_.assign(c, 0.0);
  if (!factored_)
    for (int r = nb; r + 1 < c; ++r)
      if (kind_[r] == RowKind::kFriction && kind_[r + 1] == RowKind::kFriction && contact_of_row_[r] == contact_of_row_[r + 1]) {
        coupling_[r] = delassus(scene, r + 1, r);
        ++r;
      }
  if (nb > 0) {
    w_bb_.resize(nb, nb);
    for (int r = 0; r < nb; ++r)
      for (int k = 0; k < nb; ++k) w_bb_(r, k) = r == k ? diagonal_[r] : delassus(scene, r, k);
    ldlt_.compute(w_bb_);
    scratch_.resize(nb);
  }

  stats_.sweeps = 0;
  for (int sweep = 0; sweep < settings.iterations; ++sweep) {
    double change = 0.0;
    // Bilateral block exactly: Δλ_B = W_BB⁻¹ (rhs_B − J_B a).
    if (nb > 0) {
      for (int r = 0; r < nb; ++r) scratch_[r] = residual(r);
      solved_ = ldlt_.solve(scratch_);
      for (int r = 0; r < nb; ++r) {
        change = std::max(change, std::abs(diagonal_[r] * solved_[r]));
        lambda_[r] += solved_[r];
        addColumn(scene, r, solved_[r], a);
      }
    }
    // Contact rows in order: normal λ_n >= 0, then its friction pair in μ λ_n's disc.
    for (int r = nb; r < c; ++r) {
      if (!(diagonal_[r] > 0.0)) continue;
      if (kind_[r] == RowKind::kNormal) {
        const double next = std::max(0.0, lambda_[r] + residual(r) / diagonal_[r]);
        const double delta = next - lambda_[r];
        if (delta != 0.0) {
          change = std::max(change, diagonal_[r] * std::abs(delta));
          lambda_[r] = next;
          addColumn(scene, r, delta, a);
        }
      } else {
        const int r2 = r + 1;  // friction rows come in pairs (t1, t2)
        const double old1 = lambda_[r], old2 = lambda_[r2];
        double l1 = old1 + residual(r) / diagonal_[r];
        double l2 = diagonal_[r2] > 0.0 ? old2 + (residual(r2) - coupling_[r] * (l1 - old1)) / diagonal_[r2] : old2;
        const double bound = mu_[r] * lambda_[normal_row_[contact_of_row_[r]]];
        const double norm = std::hypot(l1, l2);
        if (norm > bound) {
          const double shrink = norm > 0.0 ? bound / norm : 0.0;
          l1 *= shrink;
          l2 *= shrink;
        }
        change = std::max({change, diagonal_[r] * std::abs(l1 - old1), diagonal_[r2] * std::abs(l2 - old2)});
        lambda_[r] = l1;
        lambda_[r2] = l2;
        if (l1 != old1) addColumn(scene, r, l1 - old1, a);
        if (l2 != old2) addColumn(scene, r2, l2 - old2, a);
        ++r;
      }
    }
    stats_.sweeps = sweep + 1;
    stats_.change = change;
    if (change <= threshold) break;
  }
  ++stats_.solves;
  stats_.total_sweeps += stats_.sweeps;
}

void UnilateralContactSolver::solve(const Scene& scene, const SceneState& s, const ConstraintRows& bilateral,
                                    const ContactSet& contacts, const BlockInverse& inverse,
                                    const Settings& settings, VecX& a) {
  buildRows(s, bilateral, contacts, settings);
  stats_.rows = rows_.rows();
  factored_ = inverse.sameOnEveryAxis() && !inverse.coupled();
  if (factored_) solveAnchorColumns(scene, inverse);
  // Body of every expanded term (after solveAnchorColumns, which borrows the buffer).
  const int terms = rows_.rows() > 0 ? rows_.end(rows_.rows() - 1) : 0;
  term_body_.resize(terms);
  for (int t = 0; t < terms; ++t) term_body_[t] = scene.bodyOfPoint(rows_.point(t));
  if (!factored_) solveRowColumns(scene, inverse);
  // On exit a = a_t + Σ_r y_r λ_r.
  iterate(scene, settings, a);
  // Contact forces for reports (on thread point A, N).
  normal_force_.assign(contacts.size(), 0.0);
  contact_force_.assign(contacts.size(), Vec3::Zero());
  for (int r = 0; r < rows_.rows(); ++r)
    if (kind_[r] != RowKind::kBilateral) {
      const int i = contact_of_row_[r];
      if (kind_[r] == RowKind::kNormal) normal_force_[i] = lambda_[r];
      contact_force_[i] += lambda_[r] * direction_[r];
    }
}

}  // namespace filum::collision
