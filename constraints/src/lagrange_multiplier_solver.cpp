#include "filum/constraints/lagrange_multiplier_solver.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include <Eigen/SparseCholesky>

#ifdef FILUM_WITH_SUITESPARSE
#include <Eigen/CholmodSupport>
#endif

#include "filum/constraints/band_solve_cost.hpp"
#include "filum/core/constraint_problem.hpp"
#include "filum/core/growing_vector.hpp"

namespace filum::constraints {

namespace {

/// FNV-1a over the bytes of an anchor's points and weights (equality is checked on a match).
std::uint64_t hashAnchor(const std::vector<int>& points, const std::vector<double>& weights) {
  std::uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const void* data, std::size_t bytes) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < bytes; ++i) h = (h ^ p[i]) * 1099511628211ull;
  };
  mix(points.data(), points.size() * sizeof(int));
  mix(weights.data(), weights.size() * sizeof(double));
  return h;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The sparse factorization of W (lower triangle, column major), its pattern kept between calls.

struct LagrangeMultiplierSolver::SparseFactor {
  using Matrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;

  explicit SparseFactor(SparseBackend backend) : backend(backend) {}

  SparseBackend backend;
  std::vector<Eigen::Triplet<double>> triplets;  // lower triangle, in assembly order
  std::vector<int> rows, cols;                   // pattern of the last matrix, assembly order
  std::vector<int> slot;                         // assembly order -> index in valuePtr()
  Matrix matrix;
  VecX factored_values;  // values of the current factorization
  bool analyzed = false, factored = false;
  Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> simplicial;
#ifdef FILUM_WITH_SUITESPARSE
  Eigen::CholmodSimplicialLDLT<Matrix, Eigen::Lower> cholmod;
#endif

  /// Builds the matrix from `triplets`; returns true when the pattern changed.
  bool assemble(int c) {
    bool same = static_cast<int>(matrix.rows()) == c && rows.size() == triplets.size();
    for (std::size_t t = 0; same && t < triplets.size(); ++t)
      same = rows[t] == triplets[t].row() && cols[t] == triplets[t].col();
    if (same) {
      double* values = matrix.valuePtr();
      for (std::size_t t = 0; t < triplets.size(); ++t) values[slot[t]] = triplets[t].value();
      return false;
    }
    matrix.resize(c, c);
    matrix.setFromTriplets(triplets.begin(), triplets.end());
    matrix.makeCompressed();
    rows.resize(triplets.size());
    cols.resize(triplets.size());
    slot.resize(triplets.size());
    for (std::size_t t = 0; t < triplets.size(); ++t) {
      rows[t] = triplets[t].row();
      cols[t] = triplets[t].col();
      const int* begin = matrix.innerIndexPtr() + matrix.outerIndexPtr()[cols[t]];
      const int* end = matrix.innerIndexPtr() + matrix.outerIndexPtr()[cols[t] + 1];
      slot[t] = static_cast<int>(std::lower_bound(begin, end, rows[t]) - matrix.innerIndexPtr());
    }
    analyzed = factored = false;
    return true;
  }

  /// Factors (analysing the pattern first if it is new) unless the values are unchanged.
  /// Returns false if the factorization failed.
  bool factor(bool& refactored) {
    const Eigen::Map<const VecX> values(matrix.valuePtr(), matrix.nonZeros());
    refactored = false;
    if (factored && factored_values.size() == values.size() &&
        std::memcmp(factored_values.data(), values.data(), sizeof(double) * values.size()) == 0)
      return true;
    refactored = true;
    bool ok = false;
#ifdef FILUM_WITH_SUITESPARSE
    if (backend == SparseBackend::kCholmod) {
      if (!analyzed) cholmod.analyzePattern(matrix);
      cholmod.factorize(matrix);
      ok = cholmod.info() == Eigen::Success;
    }
#endif
    if (backend == SparseBackend::kSimplicialLdlt) {
      if (!analyzed) simplicial.analyzePattern(matrix);
      simplicial.factorize(matrix);
      ok = simplicial.info() == Eigen::Success;
    }
    analyzed = true;
    factored = ok;
    factored_values = values;
    return ok;
  }

  void solve(Eigen::Ref<const VecX> rhs, Eigen::Ref<VecX> x) {
#ifdef FILUM_WITH_SUITESPARSE
    if (backend == SparseBackend::kCholmod) {
      x = cholmod.solve(rhs);
      return;
    }
#endif
    x = simplicial.solve(rhs);
  }
};

// ---------------------------------------------------------------------------------------------

bool LagrangeMultiplierSolver::cholmodAvailable() {
#ifdef FILUM_WITH_SUITESPARSE
  return true;
#else
  return false;
#endif
}

LagrangeMultiplierSolver::LagrangeMultiplierSolver() : LagrangeMultiplierSolver(Options()) {}

LagrangeMultiplierSolver::LagrangeMultiplierSolver(Options options)
    : options_(options), sparse_(std::make_unique<SparseFactor>(options.backend)) {}

LagrangeMultiplierSolver::~LagrangeMultiplierSolver() = default;

std::unique_ptr<LagrangeMultiplierSolver> LagrangeMultiplierSolver::fromParams(const Params& p) {
  Options o;
  o.sparse_above = p.integer("sparse_above", 0, o.sparse_above);
  o.drop_tolerance = p.nonNegative({"drop_tolerance", "1"}, o.drop_tolerance);
  if (o.drop_tolerance > 1e-6)
    p.fail("drop_tolerance", "a relative tolerance in [0, 1e-6] (entries of W below round-off, see "
                             "lagrange_multiplier_solver.hpp; larger values change the solution)");
  o.reuse = p.boolean("reuse", o.reuse);
  o.point_blocks = p.boolean("point_blocks", o.point_blocks);
  const std::string method = p.string("contact_method", "newton");
  if (method == "gauss_seidel")
    o.contact_method = ContactMethod::kGaussSeidel;
  else if (method != "newton")
    p.fail("contact_method", "\"newton\" or \"gauss_seidel\"", "\"" + method + "\"");
  o.newton_iterations = p.integer("newton_iterations", 1, o.newton_iterations);
  o.newton_damping = p.nonNegative({"newton_damping", "1"}, o.newton_damping);
  if (o.newton_damping > 1e-3)
    p.fail("newton_damping", "a proximal shift in [0, 1e-3] (relative to J's unit diagonal; larger ones slow Newton to "
                             "Gauss-Seidel's pace)");
  o.newton_presweeps = p.integer("newton_presweeps", 0, 1000, o.newton_presweeps,
                                 "Gauss-Seidel sweeps before Newton (0: none)");
  o.newton_rows = p.integer("newton_rows", 0, o.newton_rows);
  const std::string linear = p.string("newton_linear_solve", "auto");
  if (linear == "dense")
    o.newton_structured = false;
  else if (linear != "auto")
    p.fail("newton_linear_solve", "\"auto\" or \"dense\"", "\"" + linear + "\"");
  o.newton_chords = p.boolean("newton_chord_steps", o.newton_chords);
  o.contact_compliance = p.nonNegative({"contact_compliance", "1"}, o.contact_compliance);
  o.friction_compliance = p.nonNegative({"friction_compliance", "1"}, o.friction_compliance);
  if (o.contact_compliance > 1.0 || o.friction_compliance > 1.0)
    p.fail(o.contact_compliance > 1.0 ? "contact_compliance" : "friction_compliance",
           "a compliance in [0, 1], relative to W's diagonal (see lagrange_multiplier_solver.hpp)");
  o.contact_iterations = p.integer("contact_iterations", 1, o.contact_iterations);
  o.contact_tolerance = p.positive({"contact_tolerance", "1"}, o.contact_tolerance);
  const std::string form = p.string("contact_form", "auto");
  if (form == "assembled")
    o.contact_form = ContactForm::kAssembled;
  else if (form == "factored")
    o.contact_form = ContactForm::kFactored;
  else if (form != "auto")
    p.fail("contact_form", "\"auto\", \"assembled\" or \"factored\"", "\"" + form + "\"");
  if (p.has("sparse_solver")) {
    const std::string name = p.string("sparse_solver");
    if (name == "cholmod") {
      if (!cholmodAvailable())
        p.fail("sparse_solver", "\"simplicial_ldlt\" (\"cholmod\" needs a build with -DFILUM_WITH_SUITESPARSE=ON)");
      o.backend = SparseBackend::kCholmod;
    } else if (name == "simplicial_ldlt") {
      o.backend = SparseBackend::kSimplicialLdlt;
    } else {
      p.fail("sparse_solver", "\"cholmod\" or \"simplicial_ldlt\"");
    }
  }
  return std::make_unique<LagrangeMultiplierSolver>(o);
}

void LagrangeMultiplierSolver::layoutColumn(const ConstraintProblem& problem, Column& column, int width) const {
  // Segments of the bodies the column touches, in body order (bodies were collected already).
  std::sort(column.bodies.begin(), column.bodies.end());
  column.bodies.erase(std::unique(column.bodies.begin(), column.bodies.end()), column.bodies.end());
  column.starts.resize(column.bodies.size());
  int size = 0;
  for (std::size_t i = 0; i < column.bodies.size(); ++i) {
    column.starts[i] = size;
    size += width * problem.bodies[column.bodies[i]].pointCount();
  }
  // y only grows: a column slot serves anchors on different bodies from call to call; the
  // segments are addressed through starts (an operator coupling bodies always asks for all of
  // them, the exact size it solves in).
  if (column.y.size() < size) column.y.resize(size);
}

void LagrangeMultiplierSolver::prepareColumns(const ConstraintProblem& problem, const ConstraintRows& rows,
                                              const BlockInverse& inverse, bool separable) {
  const auto& bodies = problem.bodies;
  const int body_count = static_cast<int>(bodies.size());
  const int count = separable ? rows.anchors() : rows.rows();
  const int width = separable ? 1 : 3;
  const bool coupled = inverse.coupled();
  const bool reuse = separable && options_.reuse && inverse.revision() >= 0 && &inverse == cached_inverse_ &&
                     inverse.revision() == cached_revision_ && cached_size_ == problem.state_size;
  if (current_.size() < static_cast<std::size_t>(count)) {
    // Grows geometrically (contact rows come and go from step to step), each new column with room
    // for every body it can touch and for a row on the two largest bodies (a contact between
    // threads): a steady step allocates nothing.
    int largest = 0;
    for (const BodyBlock& body : bodies) largest = std::max(largest, body.pointCount());
    const std::size_t old = current_.size();
    current_.resize(2 * static_cast<std::size_t>(count));
    for (std::size_t i = old; i < current_.size(); ++i) {
      current_[i].bodies.reserve(body_count);
      current_[i].starts.reserve(body_count);
      current_[i].y.resize(2 * 3 * largest);
    }
  }
  body_touched_.assign(body_count, 0);
  // Notes that a column touches body b (terms come grouped by body: a repeat of the last one is
  // skipped, so the list stays within its reserved room; layoutColumn sorts and dedups it).
  auto addBody = [](Column& column, int b) {
    if (column.bodies.empty() || column.bodies.back() != b) column.bodies.push_back(b);
  };

  for (int i = 0; i < count; ++i) {
    Column& col = current_[i];
    col.ready = false;
    col.from = -1;
    col.bodies.clear();
    if (coupled) {
      // The operator couples bodies: every column lives on the whole scene.
      for (int b = 0; b < body_count; ++b) col.bodies.push_back(b);
    } else if (separable) {
      col.points.clear();
      col.weights.clear();
      for (int k = rows.anchorBegin(i); k < rows.anchorEnd(i); ++k) {
        col.points.push_back(rows.anchorPoint(k));
        col.weights.push_back(rows.anchorWeight(k));
        addBody(col, point_body_[rows.anchorPoint(k)]);
      }
      col.hash = hashAnchor(col.points, col.weights);
    } else {
      for (int t = rows.begin(i); t < rows.end(i); ++t) addBody(col, point_body_[rows.point(t)]);
    }
    layoutColumn(problem, col, width);
    for (int b : col.bodies) body_touched_[b] = 1;

    // Take over y from the previous call if the same anchor was solved there.
    if (!reuse) continue;
    auto it = std::lower_bound(previous_index_.begin(), previous_index_.end(), std::make_pair(col.hash, -1));
    for (; it != previous_index_.end() && it->first == col.hash; ++it) {
      Column& old = previous_[it->second];
      if (old.taken || old.points != col.points || old.weights != col.weights) continue;
      std::swap(col.y, old.y);
      old.taken = true;
      col.ready = true;
      col.from = it->second;
      ++stats_.reused_columns;
      break;
    }
  }

  // Solve the columns that are not ready.
  if (coupled) {
    for (int i = 0; i < count; ++i) {
      Column& col = current_[i];
      if (col.ready) continue;
      col.y.setZero();
      for (int t = rows.begin(i); t < rows.end(i); ++t) col.y.segment<3>(3 * rows.point(t)) += rows.coeff(t);
      inverse.solveAll(col.y);
      col.ready = true;
      ++stats_.solved_columns;
    }
    return;
  }
  // Group (column, body) jobs by body.
  bucket_start_.assign(body_count + 1, 0);
  for (int i = 0; i < count; ++i)
    if (!current_[i].ready)
      for (int b : current_[i].bodies) ++bucket_start_[b + 1];
  for (int b = 0; b < body_count; ++b) bucket_start_[b + 1] += bucket_start_[b];
  bucket_.resize(bucket_start_[body_count]);
  cursor_.assign(bucket_start_.begin(), bucket_start_.end() - 1);
  for (int i = 0; i < count; ++i)
    if (!current_[i].ready)
      for (int b : current_[i].bodies) bucket_[cursor_[b]++] = i;

  for (int b = 0; b < body_count; ++b) {
    const BodyBlock& body = bodies[b];
    const int n = body.pointCount();
    const int offset = body.offset();
    const int first = bucket_start_[b], last = bucket_start_[b + 1];
    if (separable) {
      // Three anchors per 3-column solve: anchor k of the chunk in coordinate column k.
      for (int chunk = first; chunk < last; chunk += 3) {
        const int m = std::min(3, last - chunk);
        block_.setZero(3 * n);
        for (int k = 0; k < m; ++k) {
          const Column& col = current_[bucket_[chunk + k]];
          for (std::size_t j = 0; j < col.points.size(); ++j) {
            const int p = col.points[j] - offset;
            if (p >= 0 && p < n) block_[3 * p + k] += col.weights[j];
          }
        }
        inverse.solveBlock(b, block_);
        for (int k = 0; k < m; ++k) {
          Column& col = current_[bucket_[chunk + k]];
          const int seg = static_cast<int>(std::find(col.bodies.begin(), col.bodies.end(), b) - col.bodies.begin());
          double* y = col.y.data() + col.starts[seg];
          for (int p = 0; p < n; ++p) y[p] = block_[3 * p + k];
        }
      }
    } else {
      // A 3n-value solve per row and body (the operator may mix x, y and z), kColumnBatch rows at
      // a time: a band's factors are then swept once for the batch (solveBlockColumns), and the
      // forward sweep starts at the batch's first touched point. Measured on the capstan held
      // (bench_realtime, perf): the column solves went from 37 % of its time to 28 %, the scene
      // from 0.73 to 0.66 ms per simulated ms; W is the same bit for bit.
      constexpr int kColumnBatch = 8;
      if (batch_.rows() < 3 * n || batch_.cols() < kColumnBatch)
        batch_.resize(std::max<Eigen::Index>(batch_.rows(), 2 * 3 * n), kColumnBatch);  // grows only
      for (int job = first; job < last; job += kColumnBatch) {
        const int m = std::min(kColumnBatch, last - job);
        auto x = batch_.topLeftCorner(3 * n, m);
        x.setZero();
        int first_point = n;
        for (int k = 0; k < m; ++k) {
          const int r = bucket_[job + k];
          for (int t = rows.begin(r); t < rows.end(r); ++t) {
            const int p = rows.point(t) - offset;
            if (p < 0 || p >= n) continue;
            x.col(k).segment<3>(3 * p) += rows.coeff(t);
            first_point = std::min(first_point, p);
          }
        }
        inverse.solveBlockColumns(b, x, first_point);
        for (int k = 0; k < m; ++k) {
          Column& col = current_[bucket_[job + k]];
          const int seg = static_cast<int>(std::find(col.bodies.begin(), col.bodies.end(), b) - col.bodies.begin());
          col.y.segment(col.starts[seg], 3 * n) = x.col(k);
        }
      }
    }
  }
  for (int i = 0; i < count; ++i)
    if (!current_[i].ready) {
      current_[i].ready = true;
      ++stats_.solved_columns;
    }
}

void LagrangeMultiplierSolver::storeEntry(int r, int k, double value) {
  // Lower triangle (k <= r). Dense: every entry. Sparse: drop what is below round-off.
  if (!stats_.sparse) {
    w_(r, k) = value;
    ++stats_.nonzeros;
    return;
  }
  if (r != k && !(std::abs(value) > options_.drop_tolerance * std::sqrt(diagonal_[r] * diagonal_[k]))) return;
  sparse_->triplets.emplace_back(r, k, value);
  ++stats_.nonzeros;
}

void LagrangeMultiplierSolver::assembleFromPointBlocks(const ConstraintRows& rows) {
  // W_rk = Σ_{t ∈ r} c_tᵀ Z_{p_t, k} with Z = H_m L_mᵀ over the m points this call's rows touch
  // (point_inverse_blocks.hpp; H_m their blocks of H, gathered once): column k of Z is
  // Σ_{t' ∈ k} H_m[:, p_t'] c_t', 36 m multiply-adds; an entry of W 3 per term of its row.
  const int c = rows.rows();
  const int terms = c > 0 ? rows.end(c - 1) : 0;
  resizeGrowing(compact_of_slot_, point_blocks_.held());
  std::fill(compact_of_slot_.begin(), compact_of_slot_.end(), -1);
  compact_slots_.clear();
  resizeGrowing(term_index_, terms);
  for (int r = 0; r < c; ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      const int slot = point_blocks_.slot(rows.point(t));
      if (compact_of_slot_[slot] < 0) {
        compact_of_slot_[slot] = static_cast<int>(compact_slots_.size());
        compact_slots_.push_back(slot);
      }
      term_index_[t] = 3 * compact_of_slot_[slot];
    }
  const int m = static_cast<int>(compact_slots_.size()), height = 3 * m;
  if (h_m_.rows() < height) {  // grows only (to at most H's own size)
    const Eigen::Index size = std::min(2 * height, 3 * PointInverseBlocks::maxPoints());
    h_m_.resize(size, size);
  }
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) h_m_.block<3, 3>(3 * i, 3 * j) = point_blocks_.block(compact_slots_[i], compact_slots_[j]);
  if (z_.rows() < height || z_.cols() < c)  // grows only, in both dimensions
    z_.resize(std::max<Eigen::Index>(z_.rows(), std::min(2 * height, 3 * PointInverseBlocks::maxPoints())),
              std::max<Eigen::Index>(z_.cols(), 2 * c));
  // (Written out: the same sum order for every entry whatever the buffers' alignment, which
  // depends on their history: W must not.)
  for (int k = 0; k < c; ++k) {
    double* z = z_.col(k).data();
    std::fill(z, z + height, 0.0);
    for (int t = rows.begin(k); t < rows.end(k); ++t) {
      const Vec3& coeff = rows.coeff(t);
      const double* h0 = h_m_.col(term_index_[t]).data();
      const double* h1 = h_m_.col(term_index_[t] + 1).data();
      const double* h2 = h_m_.col(term_index_[t] + 2).data();
      for (int i = 0; i < height; ++i) z[i] += h0[i] * coeff[0] + h1[i] * coeff[1] + h2[i] * coeff[2];
    }
  }
  for (int k = 0; k < c; ++k) {
    const double* z = z_.col(k).data();
    for (int r = k; r < c; ++r) {
      double sum = 0.0;
      for (int t = rows.begin(r); t < rows.end(r); ++t) {
        const Vec3& coeff = rows.coeff(t);
        const double* zt = z + term_index_[t];
        sum += coeff[0] * zt[0] + coeff[1] * zt[1] + coeff[2] * zt[2];
      }
      w_(r, k) = sum;
    }
  }
  for (int r = 0; r < c; ++r) diagonal_[r] = w_(r, r);
  stats_.nonzeros += static_cast<long>(c) * (c + 1) / 2;
}

void LagrangeMultiplierSolver::assembleSeparable(const ConstraintProblem& problem, const ConstraintRows& rows) {
  const int anchors = rows.anchors();
  const int c = rows.rows();
  const auto& bodies = problem.bodies;

  // G_ab = w_aᵀ y_b = Σ_j w_{a,j} y_b(p_j) for a >= b (0 when they share no body).
  if (g_.rows() < anchors) g_.resize(anchors, anchors);  // grows only: no allocation in steady steps
  for (int a = 0; a < anchors; ++a) {
    const Column& ca = current_[a];
    for (int b = 0; b <= a; ++b) {
      const Column& cb = current_[b];
      double sum = 0.0;
      for (std::size_t j = 0; j < ca.points.size(); ++j) {
        const int p = ca.points[j];
        const int body = point_body_[p];
        for (std::size_t seg = 0; seg < cb.bodies.size(); ++seg)
          if (cb.bodies[seg] == body) sum += ca.weights[j] * cb.y[cb.starts[seg] + p - bodies[body].offset()];
      }
      g_(a, b) = sum;
      g_(b, a) = sum;
    }
  }

  // W_rk = Σ_{f ∈ r} Σ_{f' ∈ k} G(a_f, a_f') (e_f · e_f').
  auto entry = [&](int r, int k) {
    double sum = 0.0;
    for (int f = rows.factorBegin(r); f < rows.factorEnd(r); ++f)
      for (int h = rows.factorBegin(k); h < rows.factorEnd(k); ++h) {
        const double gab = g_(rows.factorAnchor(f), rows.factorAnchor(h));
        if (gab != 0.0) sum += gab * rows.factorDirection(f).dot(rows.factorDirection(h));
      }
    return sum;
  };
  for (int r = 0; r < c; ++r) diagonal_[r] = entry(r, r);
  for (int r = 0; r < c; ++r)
    for (int k = 0; k <= r; ++k) storeEntry(r, k, k == r ? diagonal_[r] : entry(r, k));
}

double LagrangeMultiplierSolver::generalEntry(const ConstraintProblem& problem, const ConstraintRows& rows, int r, int k) const {
  // W_rk = L_r · y_k = Σ_{t ∈ r} c_t · y_k(p_t).
  const auto& bodies = problem.bodies;
  const Column& col = current_[k];
  double sum = 0.0;
  for (int t = rows.begin(r); t < rows.end(r); ++t) {
    const int p = rows.point(t);
    const int body = point_body_[p];
    for (std::size_t seg = 0; seg < col.bodies.size(); ++seg)
      if (col.bodies[seg] == body)
        sum += rows.coeff(t).dot(col.y.segment<3>(col.starts[seg] + 3 * (p - bodies[body].offset())));
  }
  return sum;
}

bool LagrangeMultiplierSolver::assembleGeneralByColumns(const ConstraintProblem& problem, const ConstraintRows& rows) {
  // Dense W with every column on the same bodies (one thread, a wire in a catheter): every pair
  // of rows couples, so W = L Y is formed as column axpys — W_{k,r} = L_r · y_k for k >= r is
  //   W_{r:c, r} = Σ_{t ∈ r} Σ_a c_t,a Y^T_{r:c, 3 p_t + a},   Y^T (c × 3N) the columns y_k as rows,
  // contiguous runs of length c − r instead of a lookup per (row, column, term) (generalEntry).
  const int c = rows.rows();
  if (stats_.sparse || c == 0) return false;
  const std::vector<int>& bodies = current_[0].bodies;
  for (int k = 1; k < c; ++k)
    if (current_[k].bodies != bodies) return false;
  const int width = 3 * problem.dof_points;
  if (yt_.rows() < c || yt_.cols() < width)  // grows only, in both dimensions
    yt_.resize(std::max<Eigen::Index>(2 * c, yt_.rows()), std::max<Eigen::Index>(width, yt_.cols()));
  if (static_cast<int>(y_start_.size()) < c) y_start_.resize(2 * c);  // grows only
  for (int b : bodies) {  // Yᵀ on the columns' bodies (the other coordinates are never read)
    const BodyBlock& body = problem.bodies[b];
    for (int k = 0; k < c; ++k) {
      const Column& col = current_[k];
      const int seg = static_cast<int>(std::find(col.bodies.begin(), col.bodies.end(), b) - col.bodies.begin());
      y_start_[k] = col.y.data() + col.starts[seg];
    }
    // Coordinate by coordinate, the c columns' entries into one contiguous column of Yᵀ (its
    // writes in order; the c reads are c sequential streams).
    for (int i = 0; i < 3 * body.pointCount(); ++i) {
      double* out = yt_.col(3 * body.offset() + i).data();
      for (int k = 0; k < c; ++k) out[k] = y_start_[k][i];
    }
  }
  for (int r = 0; r < c; ++r) {
    auto column = w_.col(r).segment(r, c - r);
    column.setZero();
    for (int t = rows.begin(r); t < rows.end(r); ++t)
      for (int a = 0; a < 3; ++a)
        if (rows.coeff(t)[a] != 0.0) column.noalias() += rows.coeff(t)[a] * yt_.col(3 * rows.point(t) + a).segment(r, c - r);
    diagonal_[r] = w_(r, r);
  }
  stats_.nonzeros += static_cast<long>(c) * (c + 1) / 2;
  return true;
}

void LagrangeMultiplierSolver::assembleGeneral(const ConstraintProblem& problem, const ConstraintRows& rows) {
  if (assembleGeneralByColumns(problem, rows)) return;
  const int c = rows.rows();
  auto entry = [&](int r, int k) { return generalEntry(problem, rows, r, k); };
  // Rows on disjoint sets of bodies do not couple (W_rk = 0: column k lives on its rows' bodies,
  // all of them when the operator couples bodies): most pairs of a scene of many threads in
  // contact, skipped without visiting their terms.
  auto share_a_body = [&](int r, int k) {
    const std::vector<int>& x = current_[r].bodies;
    const std::vector<int>& y = current_[k].bodies;
    for (int bx : x)
      if (std::find(y.begin(), y.end(), bx) != y.end()) return true;
    return false;
  };
  for (int r = 0; r < c; ++r) diagonal_[r] = entry(r, r);
  for (int r = 0; r < c; ++r)
    for (int k = 0; k <= r; ++k) {
      if (k == r)
        storeEntry(r, k, diagonal_[r]);
      else if (!share_a_body(r, k))
        storeEntry(r, k, 0.0);  // dense: an explicit zero; sparse: dropped
      else
        storeEntry(r, k, entry(r, k));
    }
}

bool LagrangeMultiplierSolver::buildEqualitySystem(const ConstraintRows& rows, const std::vector<int>& solved,
                                                   const ConstraintProblem& problem, const BlockInverse& inverse,
                                                   double dense_cost) {
  // [A −L_Bᵀ; L_B 0] [u; λ_B] = [0; β_B]: eliminating u gives L_B A⁻¹ L_Bᵀ λ_B = W_BB λ_B = β_B,
  // so each row's form is J_r = W_r, with no shift (the rows are exact; a row dependent on earlier
  // ones gives a zero pivot, refused). Every pivot is positive when A is definite — A's own, then
  // each row's, a pivot of L A⁻¹ Lᵀ's LDLᵀ — and the elimination without pivoting stable; a pivot
  // <= 0 (an indefinite A: a compressed thread; dependent rows) is refused too
  // (equality_pivot_refused_), and W is formed and factored densely with pivoting — not by the
  // sparse factorization, which pivots for sparsity only. Taken when the envelope
  // LU costs fewer multiply-adds than the band solve per row that forming W_BB takes (c S) plus
  // `dense_cost`.
  // Only for more rows than sparse_above: below, W (or W_BB) is small and factored densely, with
  // pivoting, which stays accurate where A is not definite (a compressed thread: catenary.json's
  // supports held to 1e-12 m that way, to 3e-10 m through this elimination without pivoting);
  // above, W would go to the sparse factorization, and a rod held along a channel at 240 rows
  // kept its points 1e-8 m off the axis that way against 1e-11 m through the band.
  const int c = rows.rows();
  const int nb = static_cast<int>(solved.size());
  equality_pivot_refused_ = false;
  if (nb <= options_.sparse_above || inverse.coupled() || !options_.newton_structured) return false;
  double solve = 0.0;  // S over the rows' bodies (not body_touched_: scatterForces reads that one)
  equality_bodies_.assign(problem.bodies.size(), 0);
  for (const int r : solved)
    for (int t = rows.begin(r); t < rows.end(r); ++t) equality_bodies_[point_body_[rows.point(t)]] = 1;
  BandBlocks band;
  for (std::size_t b = 0; b < problem.bodies.size(); ++b)
    if (equality_bodies_[b]) {
      if (!inverse.bandBlocks(static_cast<int>(b), band)) return false;
      solve += bandSolveMultiplyAdds(band);
    }
  band_position_.assign(c, -1);
  equality_forms_.resize(c);
  for (int i = 0; i < nb; ++i) {
    const int r = solved[i];
    band_position_[r] = i;
    equality_forms_[r] = NewtonRowForm();
    equality_forms_[r].addW(r, 1.0);
  }
  if (!equality_system_.build(rows, solved, band_position_, equality_forms_, 0.0, inverse, problem, point_body_) ||
      !(equality_system_.cost() < solve * nb + dense_cost))
    return false;
  equality_pivot_refused_ = !equality_system_.factor(/*positive_pivots=*/true);
  return !equality_pivot_refused_;
}

bool LagrangeMultiplierSolver::solveEqualitiesThroughBand(const ConstraintProblem& problem, const ConstraintRows& rows,
                                                          const BlockInverse& inverse, const VecX& a) {
  // Against the columns' path's first stage alone (c S): W's factorization would come on top.
  const int c = rows.rows();
  band_rows_.resize(c);
  for (int r = 0; r < c; ++r) band_rows_[r] = r;
  if (!buildEqualitySystem(rows, band_rows_, problem, inverse, 0.0)) return false;
  for (int r = 0; r < c; ++r) lambda_[r] = rows.rhs(r) - rows.dot(r, a);
  equality_system_.solve(lambda_.head(c));
  if (!lambda_.head(c).allFinite()) return false;  // the columns' path below takes the system
  body_touched_ = equality_bodies_;  // every row is one of them: the bodies scatterForces solves on
  stats_.equality_band = true;
  stats_.sparse = false;
  stats_.columns = 0;
  return true;
}

void LagrangeMultiplierSolver::factorAndSolve() {
  const int c = c_;
  if (!stats_.sparse) {
    // Dense LDLᵀ of the lower triangle, kept while W is unchanged.
    bool same = w_factored_.rows() == c;
    for (int k = 0; k < c && same; ++k)
      for (int r = k; r < c && same; ++r) same = w_factored_(r, k) == w_(r, k);
    if (!same) {
      w_factored_ = w_.topLeftCorner(c, c);
      ldlt_.compute(w_factored_);
      stats_.refactored = true;
    }
    if (ldlt_.info() != Eigen::Success) {
      lambda_.head(c).setConstant(std::numeric_limits<double>::quiet_NaN());  // reported by the scene
      return;
    }
    lambda_.head(c) = ldlt_.solve(rhs_.head(c));
    return;
  }
  sparse_->assemble(c);
  bool refactored = false;
  if (!sparse_->factor(refactored)) {
    lambda_.head(c).setConstant(std::numeric_limits<double>::quiet_NaN());
    stats_.refactored = refactored;
    return;
  }
  stats_.refactored = refactored;
  sparse_->solve(rhs_.head(c), lambda_.head(c));
}

void LagrangeMultiplierSolver::buildAdjacency(int c) {
  // Full symmetric rows of W from its lower triangle: entry (r, k), k <= r, serves row r at k and
  // row k at r. Counting pass, then fill (capacity kept from call to call).
  adjacency_start_.assign(c + 1, 0);
  auto count = [&](int r, int k) {
    ++adjacency_start_[r + 1];
    if (r != k) ++adjacency_start_[k + 1];
  };
  if (stats_.sparse) {
    for (const auto& t : sparse_->triplets) count(t.row(), t.col());
  } else {
    for (int k = 0; k < c; ++k)
      for (int r = k; r < c; ++r) count(r, k);
  }
  for (int r = 0; r < c; ++r) adjacency_start_[r + 1] += adjacency_start_[r];
  adjacency_column_.resize(adjacency_start_[c]);
  adjacency_value_.resize(adjacency_start_[c]);
  cursor_.assign(adjacency_start_.begin(), adjacency_start_.end() - 1);
  auto put = [&](int r, int k, double value) {
    adjacency_column_[cursor_[r]] = k;
    adjacency_value_[cursor_[r]++] = value;
    if (r == k) return;
    adjacency_column_[cursor_[k]] = r;
    adjacency_value_[cursor_[k]++] = value;
  };
  if (stats_.sparse) {
    for (const auto& t : sparse_->triplets) put(t.row(), t.col(), t.value());
  } else {
    for (int k = 0; k < c; ++k)
      for (int r = k; r < c; ++r) put(r, k, w_(r, k));
  }
}

double LagrangeMultiplierSolver::delassusRow(int r) const {
  double sum = 0.0;
  for (int i = adjacency_start_[r]; i < adjacency_start_[r + 1]; ++i) sum += adjacency_value_[i] * lambda_[adjacency_column_[i]];
  return sum;
}

bool LagrangeMultiplierSolver::factoredFormIsCheaper(const ConstraintProblem& problem, const ConstraintRows& rows) {
  // Per sweep, a row costs the rows it couples to in assembled form (about Σ over its bodies of
  // the rows on that body), 3 × the points of its bodies in factored form (plus its terms in
  // both); the assembly's O(c² terms) is left out: it only favours the factored form further.
  const auto& bodies = problem.bodies;
  rows_on_body_.assign(bodies.size(), 0);
  for (int r = 0; r < rows.rows(); ++r)
    for (int b : current_[r].bodies) ++rows_on_body_[b];
  long assembled = 0, factored = 0;
  for (int r = 0; r < rows.rows(); ++r)
    for (int b : current_[r].bodies) {
      assembled += rows_on_body_[b];
      factored += 3L * bodies[b].pointCount();
    }
  return factored < assembled;
}

/// W through its assembled rows (adjacency_): (W λ)_r = Σ_k W_rk λ_k.
struct LagrangeMultiplierSolver::AssembledDelassus {
  LagrangeMultiplierSolver& solver;
  void begin() {}
  double product(int r) const { return solver.delassusRow(r); }
  void changed(int /*r*/, double /*delta*/) {}
  /// W_BB of the equality rows (sorted) from W's rows.
  void equalityBlock(const ConstraintRows& rows, MatX& block) const {
    const auto& eq = solver.equality_rows_;
    const int nb = static_cast<int>(eq.size());
    block.setZero(nb, nb);
    for (int i = 0; i < nb; ++i) {
      const int r = eq[i];
      for (int e = solver.adjacency_start_[r]; e < solver.adjacency_start_[r + 1]; ++e) {
        const int k = solver.adjacency_column_[e];
        if (rows.kind(k) != ConstraintRows::Kind::kEquality) continue;
        const int j = static_cast<int>(std::lower_bound(eq.begin(), eq.end(), k) - eq.begin());
        block(i, j) = solver.adjacency_value_[e];
      }
    }
  }
};

/// W through its dense columns (the dense path, c <= sparse_above): (W λ)_r = W_{:,r} · λ, one
/// contiguous dot product per row — the rows of one thread all couple, so W is dense in fact
/// and a gather through adjacency_ would cost as many terms, without vector instructions.
struct LagrangeMultiplierSolver::DenseDelassus {
  LagrangeMultiplierSolver& solver;
  void begin() {
    // The lower triangle mirrored into the upper one: column r is then all of row r.
    const int c = solver.c_;
    for (int k = 0; k < c; ++k) solver.w_.col(k).segment(0, k) = solver.w_.row(k).segment(0, k).transpose();
  }
  double product(int r) const { return solver.w_.col(r).head(solver.c_).dot(solver.lambda_.head(solver.c_)); }
  void changed(int /*r*/, double /*delta*/) {}
  /// W_BB of the equality rows (sorted).
  void equalityBlock(const ConstraintRows& /*rows*/, MatX& block) const {
    const auto& eq = solver.equality_rows_;
    const int nb = static_cast<int>(eq.size());
    block.resize(nb, nb);
    for (int i = 0; i < nb; ++i)
      for (int j = 0; j < nb; ++j) block(i, j) = solver.w_(eq[i], eq[j]);
  }
};

/// W = L A⁻¹ Lᵀ never assembled: u = A⁻¹ Lᵀ λ = Σ_r λ_r y_r is kept up to date, (W λ)_r = L_r·u
/// costs the row's terms, a change of λ_r adds Δ y_r on the row's bodies — per row O(terms + the
/// points of its bodies) instead of O(rows it couples to), and no O(c²) assembly.
struct LagrangeMultiplierSolver::FactoredDelassus {
  LagrangeMultiplierSolver& solver;
  const ConstraintProblem& problem;
  const ConstraintRows& rows;
  VecX& u;
  void begin() {
    // Each body's first coordinate and size, looked up once per solve instead of per update.
    solver.body_span_.clear();
    for (const BodyBlock& body : problem.bodies) solver.body_span_.emplace_back(3 * body.offset(), 3 * body.pointCount());
    u.setZero(3 * problem.dof_points);
    for (int r = 0; r < rows.rows(); ++r) changed(r, solver.lambda_[r]);
  }
  double product(int r) const { return rows.dot(r, u); }
  void changed(int r, double delta) {
    if (delta == 0.0) return;
    const Column& col = solver.current_[r];
    for (std::size_t seg = 0; seg < col.bodies.size(); ++seg) {
      const auto [first, size] = solver.body_span_[col.bodies[seg]];
      u.segment(first, size) += delta * col.y.segment(col.starts[seg], size);
    }
  }
  void equalityBlock(const ConstraintRows& /*rows*/, MatX& block) const {
    const auto& eq = solver.equality_rows_;
    const int nb = static_cast<int>(eq.size());
    block.resize(nb, nb);
    for (int i = 0; i < nb; ++i)
      for (int j = 0; j <= i; ++j) block(i, j) = block(j, i) = solver.generalEntry(problem, rows, eq[i], eq[j]);
  }
};

/// W through the band (BandDelassusProduct), for reads in bulk: a change of λ makes the next
/// product recompute all of W λ (one band product, O(terms + Σ_b groups_b · range_b)). It serves
/// the equality polish after a Newton solve that never formed W (the equality rows' products, then
/// every row's residual: two products), not Gauss–Seidel's sweeps, which change λ row by row.
struct LagrangeMultiplierSolver::BandProductDelassus {
  LagrangeMultiplierSolver& solver;
  const ConstraintProblem& problem;
  const ConstraintRows& rows;
  bool stale = true;  // band_wl_ is not W λ of the current λ
  void begin() { stale = true; }
  double product(int r) {
    if (stale) {
      const int c = solver.c_;
      if (solver.band_wl_.size() < c) solver.band_wl_.resize(2 * c);  // grows only
      solver.band_product_.multiply(rows, solver.lambda_.head(c), solver.band_wl_.head(c));
      stale = false;
    }
    return solver.band_wl_[r];
  }
  void changed(int /*r*/, double delta) { stale = stale || delta != 0.0; }
  /// W λ of the current λ, known (the same bits as product() would compute: the same product).
  void set(const Eigen::Ref<const VecX>& w_lambda) {
    const int c = solver.c_;
    if (solver.band_wl_.size() < c) solver.band_wl_.resize(2 * c);  // grows only
    solver.band_wl_.head(c) = w_lambda;
    stale = false;
  }
  /// W_BB of the equality rows (sorted): from A⁻¹'s band where it reaches, else by columns.
  void equalityBlock(const ConstraintRows& rows, MatX& block) {
    const auto& eq = solver.equality_rows_;
    const int nb = static_cast<int>(eq.size()), c = solver.c_;
    block.resize(nb, nb);
    // W_ij (i >= j) from A⁻¹'s band where W's diagonal came from it and the two rows' points lie
    // within its range (a fixed point's three rows on one point); a column W e_j by a product
    // through the band for each row j with a later row further apart (the clamps at a
    // catheter's two ends: one cluster's columns, not every row's). The upper triangle mirrors.
    auto& column = solver.block_column_;
    column.assign(nb, solver.source_ == DelassusSource::kInverseBand ? 0 : 1);
    for (int j = 0; j < nb; ++j)
      for (int i = j; i < nb && !column[j]; ++i)
        if (!solver.inverseBandEntry(rows, eq[i], eq[j], block(i, j))) column[j] = 1;
    int products = 0;
    for (int j = 0; j < nb; ++j) {
      if (!column[j]) continue;
      if (products++ == 0) {
        if (solver.band_wl_.size() < c) solver.band_wl_.resize(2 * c);  // grows only
        if (solver.unit_.size() < c) solver.unit_.resize(2 * c);
        solver.unit_.head(c).setZero();
      }
      solver.unit_[eq[j]] = 1.0;
      solver.band_product_.multiply(rows, solver.unit_.head(c), solver.band_wl_.head(c));
      solver.unit_[eq[j]] = 0.0;
      for (int i = j; i < nb; ++i) block(i, j) = solver.band_wl_[eq[i]];
    }
    for (int j = 0; j < nb; ++j)
      for (int i = 0; i < j; ++i) block(i, j) = block(j, i);
    solver.stats_.block_products = products;
    if (products > 0) stale = true;
  }
};

/// W for the contact Newton, formed the first time it is asked for (a dense LU step; products,
/// when the band's are not cheaper), at most once per solve. `asked` tells whether this solve's
/// arithmetic went through W: what follows (Gauss–Seidel, the polish) then reads W too, so that a
/// solve repeats bit for bit whether W was formed in it or kept from the last call.
class LagrangeMultiplierSolver::DeferredDelassus final : public DelassusEntries {
 public:
  DeferredDelassus(LagrangeMultiplierSolver& solver, const ConstraintProblem& problem, const ConstraintRows& rows,
                   const BlockInverse& inverse)
      : solver_(solver), problem_(problem), rows_(rows), inverse_(inverse) {}
  /// W, both triangles: formed now (lower triangle, as step 2 forms it) unless w_ holds it —
  /// formed in step 2 or kept from the last call, whichever kind of call that was — and its
  /// lower triangle mirrored into the upper one on the first ask.
  const MatX& matrix() override {
    if (!asked_) {
      solver_.formDelassus(problem_, rows_, inverse_);
      DenseDelassus{solver_}.begin();
    }
    asked_ = true;
    return solver_.w_;
  }
  bool asked() const { return asked_; }
  /// Asked in this solve: a W kept from the last call counts as unformed, so that the solve's
  /// choices do not depend on what was kept (a run restored from a saved state repeats bit for bit).
  bool formed() const override { return asked_; }

 private:
  LagrangeMultiplierSolver& solver_;
  const ConstraintProblem& problem_;
  const ConstraintRows& rows_;
  const BlockInverse& inverse_;
  bool asked_ = false;
};

double LagrangeMultiplierSolver::pointBlockEntry(const ConstraintRows& rows, int r, int k) const {
  double sum = 0.0;
  for (int t = rows.begin(r); t < rows.end(r); ++t) {
    const int slot = point_blocks_.slot(rows.point(t));
    for (int u = rows.begin(k); u < rows.end(k); ++u)
      sum += rows.coeff(t).dot(point_blocks_.block(slot, point_blocks_.slot(rows.point(u))) * rows.coeff(u));
  }
  return sum;
}

double LagrangeMultiplierSolver::inverseBandDiagonal(const ConstraintRows& rows, int r) const {
  if (far_row_[r] >= 0) return far_diagonal_[far_row_[r]];
  double entry = 0.0;
  inverseBandEntry(rows, r, r, entry);  // (a row not far lies within the range on every body)
  return entry;
}

bool LagrangeMultiplierSolver::inverseBandEntry(const ConstraintRows& rows, int r, int k, double& entry) const {
  // W_rk = Σ_{t ∈ r} Σ_{u ∈ k} c_tᵀ (A⁻¹)(p_t, p_u) c_u over the pairs on one body (A⁻¹ is block
  // diagonal over the bodies), each block read from the body's inverse band: false when a pair
  // lies further apart than the range taken there.
  entry = 0.0;
  for (int t = rows.begin(r); t < rows.end(r); ++t) {
    const int body = point_body_[rows.point(t)];
    const BandBlocks& band = inverse_band_layout_[body];
    const std::vector<Eigen::Matrix3d>& z = inverse_band_[body];
    const int range = inverse_range_[body];
    const int offset = problem_offset_[body];
    const int gt = band.point_group[rows.point(t) - offset];
    for (int u = rows.begin(k); u < rows.end(k); ++u) {
      if (point_body_[rows.point(u)] != body) continue;
      const int gu = band.point_group[rows.point(u) - offset];
      if (std::abs(gt - gu) > range) return false;
      // Block (gt, gu): stored as (max, min), the one above the diagonal its transpose.
      const Eigen::Matrix3d& block = z[static_cast<std::size_t>(std::max(gt, gu)) * (range + 1) +
                                       (std::min(gt, gu) - std::max(gt, gu) + range)];
      entry += gt >= gu ? rows.coeff(t).dot(block * rows.coeff(u)) : rows.coeff(u).dot(block * rows.coeff(t));
    }
  }
  return true;
}

template <class Visit>
void LagrangeMultiplierSolver::forEachRowSpan(const ConstraintRows& rows, int r, Visit&& visit) const {
  // For each body row r acts on: the widest |g_t − g_u| between two of its points on that body,
  // in the body's band order (0 for a row on one point of it).
  for (int t = rows.begin(r); t < rows.end(r); ++t) {
    const int body = point_body_[rows.point(t)];
    bool seen = false;  // the body came earlier in the row: visited then
    for (int u = rows.begin(r); u < t && !seen; ++u) seen = point_body_[rows.point(u)] == body;
    if (seen) continue;
    const BandBlocks& band = inverse_band_layout_[body];
    const int offset = problem_offset_[body];
    int lowest = band.point_group[rows.point(t) - offset], highest = lowest;
    for (int u = t + 1; u < rows.end(r); ++u) {
      if (point_body_[rows.point(u)] != body) continue;
      const int g = band.point_group[rows.point(u) - offset];
      lowest = std::min(lowest, g);
      highest = std::max(highest, g);
    }
    visit(body, highest - lowest);
  }
}

bool LagrangeMultiplierSolver::inverseBandCovers(const ConstraintProblem& problem, const ConstraintRows& rows,
                                                 const BlockInverse& inverse) {
  const int bodies = static_cast<int>(problem.bodies.size());
  if (static_cast<int>(inverse_band_.size()) < bodies) {  // grows only
    inverse_band_.resize(bodies);
    inverse_band_layout_.resize(bodies);
    problem_offset_.resize(bodies);
    inverse_range_.resize(bodies);
    span_rows_.resize(static_cast<std::size_t>(bodies) * (kWidestInverseRange + 1));
  }
  body_touched_.assign(bodies, 0);  // (whole before any return: scatterForces reads it)
  for (int r = 0; r < rows.rows(); ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) body_touched_[point_body_[rows.point(t)]] = 1;
  for (int b = 0; b < bodies; ++b) {
    if (!body_touched_[b]) continue;
    if (!inverse.bandBlocks(b, inverse_band_layout_[b])) return false;
    problem_offset_[b] = problem.bodies[b].offset();
  }
  // The range of A⁻¹'s blocks taken on each body. A row a few groups wider than the band (a
  // point inside a tube's chord between two sphere centres in two segments of a rod: three nodes,
  // four groups with the frames between them, where the band reaches two) would take a solve of
  // its own; Takahashi's recurrence reaches R >= r block diagonals for 27 r (R − r) more
  // multiply-adds per group (BlockBandLdlt::inverseBand), a far row's solve costs 9 (2 r + 1) per
  // group (bandSolveMultiplyAdds). R is the span up to kWidestInverseRange whose rows save the most
  // over the wider recurrence's cost; rows reaching further (a self-contact) stay far. A row that
  // reaches further than that on another body keeps its solve on every body: not counted.
  std::fill(span_rows_.begin(), span_rows_.begin() + static_cast<std::ptrdiff_t>(bodies) * (kWidestInverseRange + 1), 0);
  for (int r = 0; r < rows.rows(); ++r) {
    bool coverable = true;
    forEachRowSpan(rows, r, [&](int, int span) { coverable = coverable && span <= kWidestInverseRange; });
    if (!coverable) continue;
    forEachRowSpan(rows, r, [&](int body, int span) {
      if (span > inverse_band_layout_[body].range)
        ++span_rows_[static_cast<std::size_t>(body) * (kWidestInverseRange + 1) + span];
    });
  }
  int widest = 0;
  for (int b = 0; b < bodies; ++b) {
    if (!body_touched_[b]) continue;
    const BandBlocks& band = inverse_band_layout_[b];
    const double solve = 9.0 * (2 * band.range + 1), widening = 27.0 * band.range;  // per group
    int best = band.range, covered = 0;
    double best_saving = 0.0;
    for (int range = band.range + 1; range <= kWidestInverseRange; ++range) {
      covered += span_rows_[static_cast<std::size_t>(b) * (kWidestInverseRange + 1) + range];
      const double saving = covered * solve - widening * (range - band.range);
      if (saving > best_saving) {
        best_saving = saving;
        best = range;
      }
    }
    inverse_range_[b] = best;
    widest = std::max(widest, best);
  }
  // The far rows: two points of one body further apart than the range taken on it.
  resizeGrowing(far_row_, rows.rows());
  resizeGrowing(far_point_mark_, point_body_.size());
  std::fill(far_point_mark_.begin(), far_point_mark_.end(), -1);
  int far_rows = 0, points = 0;  // the far rows, and the distinct points of all rows
  for (int r = 0; r < rows.rows(); ++r) {
    bool far = false;
    forEachRowSpan(rows, r, [&](int body, int span) { far = far || span > inverse_range_[body]; });
    far_row_[r] = far ? far_rows++ : -1;
    for (int t = rows.begin(r); t < rows.end(r); ++t) {
      int& mark = far_point_mark_[rows.point(t)];
      if (mark < 0) ++points;
      mark = r;
    }
  }
  // A far row costs one solve; the columns cost one per row (c >= the far rows), the point blocks
  // three per distinct point of all rows: the band is left only when those are fewer.
  if (far_rows > 3 * points) return false;
  stats_.far_rows = far_rows;
  stats_.inverse_range = widest;
  return true;
}

void LagrangeMultiplierSolver::computeInverseBands(const ConstraintProblem& problem, const ConstraintRows& rows,
                                                   const BlockInverse& inverse) {
  // (inverseBandCovers found a band on every touched body: inverseBandBlocks has one too.)
  for (std::size_t b = 0; b < problem.bodies.size(); ++b)
    if (body_touched_[b]) inverse.inverseBandBlocks(static_cast<int>(b), inverse_range_[b], inverse_band_[b]);
  // A far row's W_rr = Σ_b l_r,b · A_b⁻¹ l_r,b over the bodies it acts on (A⁻¹ block diagonal over
  // the bodies): the same solve as its column's (prepareColumns), for this row alone.
  far_diagonal_.clear();
  for (int r = 0; r < rows.rows(); ++r) {
    if (far_row_[r] < 0) continue;
    double sum = 0.0;
    for (int b = 0; b < static_cast<int>(problem.bodies.size()); ++b) {
      bool acts = false;
      for (int t = rows.begin(r); t < rows.end(r) && !acts; ++t) acts = point_body_[rows.point(t)] == b;
      if (!acts) continue;
      const int size = 3 * problem.bodies[b].pointCount(), offset = problem_offset_[b];
      if (far_work_.size() < size) far_work_.resize(2 * size);  // grows only
      auto x = far_work_.head(size);
      x.setZero();
      for (int t = rows.begin(r); t < rows.end(r); ++t)
        if (point_body_[rows.point(t)] == b) x.segment<3>(3 * (rows.point(t) - offset)) += rows.coeff(t);
      inverse.solveBlock(b, x);
      for (int t = rows.begin(r); t < rows.end(r); ++t)
        if (point_body_[rows.point(t)] == b) sum += rows.coeff(t).dot(x.segment<3>(3 * (rows.point(t) - offset)));
    }
    far_diagonal_.push_back(sum);
  }
}

double LagrangeMultiplierSolver::diagonalEntry(const ConstraintProblem& problem, const ConstraintRows& rows, int r) const {
  switch (source_) {
    case DelassusSource::kPointBlocks: return pointBlockEntry(rows, r, r);
    case DelassusSource::kInverseBand: return inverseBandDiagonal(rows, r);
    case DelassusSource::kColumns: break;
  }
  return generalEntry(problem, rows, r, r);
}

bool LagrangeMultiplierSolver::choosePointBlocks(const ConstraintProblem& problem, const ConstraintRows& rows,
                                                 const BlockInverse& inverse) {
  const int c = rows.rows();
  const bool separable = inverse.sameOnEveryAxis() && !inverse.coupled();
  if (separable || inverse.coupled() || stats_.sparse || !options_.point_blocks || c == 0) return false;
  point_blocks_.keepIfUnchanged(inverse, problem);
  const double missing = point_blocks_.listMissing(rows), m = point_blocks_.touched();
  double solve = 0.0;  // S
  body_touched_.assign(problem.bodies.size(), 0);
  for (int r = 0; r < c; ++r)
    for (int t = rows.begin(r); t < rows.end(r); ++t) body_touched_[point_body_[rows.point(t)]] = 1;
  BandBlocks band;
  for (std::size_t b = 0; b < problem.bodies.size(); ++b)
    if (body_touched_[b])
      solve += inverse.bandBlocks(static_cast<int>(b), band) ? bandSolveMultiplyAdds(band)
                                                            : 63.0 * problem.bodies[b].pointCount();
  const double by_columns = solve * c, through_points = 3.0 * m * solve + 36.0 * m * c + 9.0 * m * m;
  if (!(through_points < by_columns) || !point_blocks_.addMissing(inverse, problem, point_body_)) return false;
  stats_.point_columns = 3 * static_cast<int>(missing);  // (body_touched_: for scatterForces)
  return true;
}

void LagrangeMultiplierSolver::formDelassus(const ConstraintProblem& problem, const ConstraintRows& rows,
                                            const BlockInverse& inverse) {
  if (!w_unformed_) return;
  const int c = rows.rows();
  if (w_.rows() < c) w_.resize(c, c);  // grows only (entries r, k < c are used)
  // Kept aside: the assembly writes diagonal_ again, with the same values but perhaps another sum
  // order than diagonalEntry's, and the solve's ρ and compliance were set from the first.
  if (saved_diagonal_.size() < c) saved_diagonal_.resize(2 * c);  // grows only
  saved_diagonal_.head(c) = diagonal_.head(c);
  // W's diagonal came from A⁻¹'s band: W itself from the point blocks or the columns, chosen as
  // step 1 would have (the point blocks kept while A is: the capstan's step matrix serves ~20 steps).
  if (source_ == DelassusSource::kInverseBand && choosePointBlocks(problem, rows, inverse)) {
    stats_.point_blocks = true;
    assembleFromPointBlocks(rows);
  } else if (source_ == DelassusSource::kPointBlocks) {
    assembleFromPointBlocks(rows);
  } else {
    if (!columns_ready_) prepareColumns(problem, rows, inverse, false);  // (kInverseBand: none yet)
    columns_ready_ = true;
    assembleGeneral(problem, rows);
  }
  diagonal_.head(c) = saved_diagonal_.head(c);
  w_unformed_ = false;
  stats_.reassembled = true;
  last_nonzeros_ = stats_.nonzeros;
}

void LagrangeMultiplierSolver::warmStart(const ConstraintRows& rows) {
  // λ of the previous call when its rows were of the same kinds (an earlier stage of the same
  // step, same contact set); else the rows' guesses (a contact's force of the previous step, 0 for
  // a new one).
  // A λ that is not finite (a failed solve: through a step matrix that is not definite, which an
  // implicit integrator then takes again in halves) is no guide: the rows start from their
  // guesses then, and a guess that is not finite (a force remembered from it) from 0.
  const int c = rows.rows();
  bool warm = static_cast<int>(last_kinds_.size()) == c && lambda_.head(c).allFinite();
  for (int r = 0; warm && r < c; ++r) warm = last_kinds_[r] == rows.kind(r);
  if (!warm)
    for (int r = 0; r < c; ++r) lambda_[r] = std::isfinite(rows.guess(r)) ? rows.guess(r) : 0.0;
  last_kinds_.resize(c);
  for (int r = 0; r < c; ++r) last_kinds_[r] = rows.kind(r);
}

void LagrangeMultiplierSolver::saveMemory(StepMemory& memory) const {
  if (memory.multipliers.capacity() < static_cast<std::size_t>(c_))  // geometric growth (StepMemory)
    memory.multipliers.reserve(std::max<std::size_t>(c_, 2 * memory.multipliers.capacity()));
  memory.multipliers.assign(lambda_.data(), lambda_.data() + c_);
  memory.row_kinds.resize(last_kinds_.size());
  for (std::size_t r = 0; r < last_kinds_.size(); ++r) memory.row_kinds[r] = static_cast<int>(last_kinds_[r]);
}

void LagrangeMultiplierSolver::restoreMemory(const StepMemory& memory) {
  const int c = static_cast<int>(memory.multipliers.size());
  if (rhs_.size() < c) {  // the row-sized buffers grow together (solve)
    rhs_.resize(2 * c);
    diagonal_.resize(2 * c);
    lambda_.conservativeResize(2 * c);
  }
  for (int r = 0; r < c; ++r) lambda_[r] = memory.multipliers[r];
  c_ = c;
  step_began_ = true;
  last_kinds_.resize(memory.row_kinds.size());
  for (std::size_t r = 0; r < memory.row_kinds.size(); ++r)
    last_kinds_[r] = static_cast<ConstraintRows::Kind>(memory.row_kinds[r]);
}

void LagrangeMultiplierSolver::setCompliance(const ConstraintRows& rows) {
  // R_r = ε W_rr on contact rows (ε_n on normal rows, ε_t on friction rows), 0 on equality rows.
  const int c = rows.rows();
  if (compliance_.size() < c) compliance_.resize(2 * c);  // grows only
  for (int r = 0; r < c; ++r) {
    const ConstraintRows::Kind kind = rows.kind(r);
    const double epsilon = kind == ConstraintRows::Kind::kNormal     ? options_.contact_compliance
                           : kind == ConstraintRows::Kind::kFriction ? options_.friction_compliance
                                                                     : 0.0;
    compliance_[r] = epsilon * std::max(diagonal_[r], 0.0);
  }
}

template <class Delassus>
double LagrangeMultiplierSolver::contactResidual(const ConstraintRows& rows, Delassus& w) {
  const int c = rows.rows();
  if (wl_.size() < c) wl_.resize(2 * c);  // grows only
  if (effective_diagonal_.size() < c) effective_diagonal_.resize(2 * c);
  for (int r = 0; r < c; ++r) {
    wl_[r] = w.product(r) + compliance_[r] * lambda_[r] - rhs_[r];
    effective_diagonal_[r] = diagonal_[r] + compliance_[r];
  }
  const double residual = newton_.residual(rows, effective_diagonal_.head(c), wl_.head(c), lambda_.head(c));
  stats_.threshold = newton_.threshold(options_.contact_tolerance, rhs_.head(c).lpNorm<Eigen::Infinity>());
  return residual;
}

template <class Delassus>
void LagrangeMultiplierSolver::solveWithContacts(const ConstraintRows& rows, Delassus& w) {
  warmStart(rows);
  setCompliance(rows);
  w.begin();
  factorEqualityBlock(rows, w);
  projectedGaussSeidel(rows, w, options_.contact_iterations);
}

template <class Delassus>
void LagrangeMultiplierSolver::projectedGaussSeidel(const ConstraintRows& rows, Delassus& w, int max_sweeps) {
  const int c = rows.rows();
  // With the compliance R (zero on equality rows): W + diag(R).
  auto residual = [&](int r) { return rhs_[r] - w.product(r) - compliance_[r] * lambda_[r]; };
  auto diagonal = [&](int r) { return diagonal_[r] + compliance_[r]; };
  auto set = [&](int r, double value) {
    w.changed(r, value - lambda_[r]);
    lambda_[r] = value;
  };

  stats_.residual = contactResidual(rows, w);
  for (int sweep = 0; sweep < max_sweeps && stats_.residual > stats_.threshold; ++sweep) {
    double change = 0.0;
    // Equality block exactly: Δλ_B = W_BB⁻¹ (β − W λ)_B.
    change = std::max(change, equalityStep(w));
    // Contact rows in order: a normal λ_n >= 0, then its friction pair in μ λ_n's disc.
    for (int r = 0; r < c; ++r) {
      const ConstraintRows::Kind kind = rows.kind(r);
      if (kind == ConstraintRows::Kind::kEquality || !(diagonal(r) > 0.0)) continue;
      if (kind == ConstraintRows::Kind::kNormal) {
        const double next = std::max(0.0, lambda_[r] + residual(r) / diagonal(r));
        change = std::max(change, diagonal(r) * std::abs(next - lambda_[r]));
        set(r, next);
        continue;
      }
      const int r2 = r + 1;  // friction rows come in pairs (t1, t2) after their normal row
      const double old1 = lambda_[r], old2 = lambda_[r2];
      double l1 = old1 + residual(r) / diagonal(r);
      set(r, l1);  // t2's residual sees t1's update (Gauss–Seidel within the pair)
      double l2 = diagonal(r2) > 0.0 ? old2 + residual(r2) / diagonal(r2) : old2;
      const double bound = rows.friction(r) * lambda_[r - 1];
      const double norm = std::sqrt(l1 * l1 + l2 * l2);  // |λ_t| (no overflow: |λ| is far below 1e150)
      if (norm > bound) {
        const double shrink = norm > 0.0 ? bound / norm : 0.0;
        l1 *= shrink;
        l2 *= shrink;
      }
      change = std::max({change, diagonal(r) * std::abs(l1 - old1), diagonal(r2) * std::abs(l2 - old2)});
      set(r, l1);
      set(r2, l2);
      ++r;
    }
    ++stats_.sweeps;
    stats_.change = change;
    // The change per sweep only says Gauss–Seidel is slow, not that it is done: the residual
    // decides, measured when the sweep changed little and every 8 sweeps (a product per row).
    constexpr int kResidualEvery = 8;
    if (change <= stats_.threshold || (sweep + 1) % kResidualEvery == 0 || sweep + 1 == max_sweeps)
      stats_.residual = contactResidual(rows, w);
  }
  stats_.converged = stats_.residual <= stats_.threshold;
}

/// Newton on W dense (both triangles mirrored by DenseDelassus::begin) or, `deferred`, on W's
/// products through the band with W formed only if Newton or Gauss–Seidel asks for it; Gauss–Seidel
/// from Newton's best iterate when it does not converge.
void LagrangeMultiplierSolver::solveWithNewton(const ConstraintProblem& problem, const ConstraintRows& rows,
                                               const BlockInverse& inverse, bool deferred) {
  const int c = rows.rows();
  warmStart(rows);
  setCompliance(rows);
  DenseDelassus dense{*this};
  BandProductDelassus band{*this, problem, rows};
  DeferredDelassus w(*this, problem, rows, inverse);
  if (deferred) {
    // W_BB and its factors as the last call left them on the same W (the same newton_key_: no
    // call since on another W, solve()).
    if (newton_key_ != equality_block_key_) {
      factorEqualityBlock(rows, band, &problem, &inverse);
    } else {
      stats_.equality_block_band = equality_by_band_;
      stats_.block_held = true;
    }
    equality_block_key_ = newton_key_;
  } else {
    equality_block_key_ = -1;  // (newton_key_ >= 0: kept for no call)
    w.matrix();  // (formed in step 2)
    factorEqualityBlock(rows, dense);
  }
  ContactNewton::Settings settings;
  settings.damping = options_.newton_damping;
  settings.structured = options_.newton_structured;
  settings.matrix_key = newton_key_;
  settings.chords = options_.newton_chords;
  const ContactNewton::Structure structure{&inverse, &problem, &point_body_, deferred ? &band_product_ : nullptr};
  // With W formed, a few Gauss–Seidel sweeps first: each row's projection onto its cone releases
  // the warm start's contacts that now pull (λ_n < 0 once w_n is counted) and moves the rest
  // towards stick or slide, so Newton starts from a better active set — it otherwise releases
  // the redundant rows of a knot about one contact per short line-search step. (Deferred, W is
  // not formed and the sweeps would form it: not done.)
  if (!deferred && options_.newton_presweeps > 0) projectedGaussSeidel(rows, dense, options_.newton_presweeps);
  // Newton, and where it stalls (its active set still moving) a few Gauss–Seidel sweeps to
  // smooth λ before the next Newton round, within newton_iterations Newton iterations in all.
  constexpr int kSmoothingSweeps = 8;
  while (true) {
    settings.iterations = options_.newton_iterations - stats_.newton_iterations;
    const ContactNewton::Result result = newton_.solve(w, diagonal_.head(c), rhs_.head(c), compliance_.head(c), rows,
                                                       settings, options_.contact_tolerance, lambda_.head(c), &structure);
    stats_.newton_iterations += result.iterations;
    stats_.structured_steps += result.structured_steps;
    stats_.chord_steps += result.chord_steps;
    stats_.residual = result.residual;
    stats_.threshold = result.threshold;
    stats_.converged = result.converged;
    if (result.converged || !result.stalled || stats_.newton_iterations >= options_.newton_iterations) break;
    w.matrix();  // Gauss–Seidel reads W's rows
    projectedGaussSeidel(rows, dense, kSmoothingSweeps);
    if (stats_.converged) break;
  }
  if (!stats_.converged) {
    stats_.fell_back = true;
    w.matrix();
    projectedGaussSeidel(rows, dense, options_.contact_iterations);
  }
  if (w.asked()) {
    polishEqualities(rows, dense);
  } else {
    band.set(newton_.lastProduct());  // W λ as Newton last measured it: no product again
    polishEqualities(rows, band);
  }
}

template <class Delassus>
void LagrangeMultiplierSolver::factorEqualityBlock(const ConstraintRows& rows, Delassus& w, const ConstraintProblem* problem,
                                                   const BlockInverse* inverse) {
  // W_BB of the equality rows, factored once per solve (Gauss–Seidel's sweeps and the polish) —
  // or, given the problem and an operator with a band, the augmented system of the equality rows
  // alone when its envelope LU is cheaper (solveEqualitiesThroughBand's, on the rows B).
  equality_rows_.clear();
  for (int r = 0; r < rows.rows(); ++r)
    if (rows.kind(r) == ConstraintRows::Kind::kEquality) equality_rows_.push_back(r);
  const int nb = static_cast<int>(equality_rows_.size());
  equality_by_band_ = false;
  if (nb == 0) return;
  // Grow only: the equality rows change in number as a channel lets a body's points go.
  if (residual_bb_.size() < nb) {
    residual_bb_.resize(2 * nb);
    delta_bb_.resize(2 * nb);
  }
  // The band's envelope LU against W_BB's band product per row and its LDLᵀ, nb³/6.
  const double dense_cost = static_cast<double>(nb) * nb * nb / 6.0;
  if (problem && inverse && buildEqualitySystem(rows, equality_rows_, *problem, *inverse, dense_cost)) {
    equality_by_band_ = true;
    stats_.equality_block_band = true;
    return;
  }
  w.equalityBlock(rows, w_bb_);
  ldlt_bb_.compute(w_bb_);
}

template <class Delassus>
double LagrangeMultiplierSolver::equalityStep(Delassus& w) {
  // Δλ_B = W_BB⁻¹ (β − W λ)_B (equality rows have no compliance); returns max W_rr |Δλ_r| (m/s²).
  const int nb = static_cast<int>(equality_rows_.size());
  if (nb == 0) return 0.0;
  for (int i = 0; i < nb; ++i) residual_bb_[i] = rhs_[equality_rows_[i]] - w.product(equality_rows_[i]);
  if (equality_by_band_) {
    delta_bb_.head(nb) = residual_bb_.head(nb);
    equality_system_.solve(delta_bb_.head(nb));
  } else {
    delta_bb_.head(nb) = ldlt_bb_.solve(residual_bb_.head(nb));
  }
  double change = 0.0;
  for (int i = 0; i < nb; ++i) {
    const int r = equality_rows_[i];
    change = std::max(change, std::abs(diagonal_[r] * delta_bb_[i]));
    w.changed(r, delta_bb_[i]);
    lambda_[r] += delta_bb_[i];
  }
  return change;
}

template <class Delassus>
void LagrangeMultiplierSolver::polishEqualities(const ConstraintRows& rows, Delassus& w) {
  // The equality rows exactly, with the contact forces as they are: Δλ_B = W_BB⁻¹ (β − Wλ)_B. The
  // iterative solve leaves them a residual of its tolerance, which a fixed point held for
  // thousands of steps would integrate into drift; the contact rows move by W_CB Δλ_B, of the
  // same small size, and the residual reported is measured after; a polish that would take a
  // converged solve past the tolerance is undone.
  const int c = rows.rows();
  const int nb = static_cast<int>(equality_rows_.size());
  if (nb == 0) return;
  // Kept only if the contact rows stay within the tolerance (a converged solve stays converged).
  const bool was_converged = stats_.converged;
  const double was_residual = stats_.residual, was_threshold = stats_.threshold;
  if (unpolished_.size() < c) unpolished_.resize(2 * c);
  unpolished_.head(c) = lambda_.head(c);
  equalityStep(w);
  stats_.residual = contactResidual(rows, w);
  stats_.converged = stats_.residual <= stats_.threshold;
  if (was_converged && !stats_.converged) {
    for (int i = 0; i < nb; ++i) w.changed(equality_rows_[i], -delta_bb_[i]);
    lambda_.head(c) = unpolished_.head(c);
    stats_.residual = was_residual;
    stats_.threshold = was_threshold;
    stats_.converged = true;
  }
}

bool LagrangeMultiplierSolver::sameRowsAsLastCall(const ConstraintRows& rows) const {
  const int c = rows.rows();
  if (c + 1 != static_cast<int>(last_row_start_.size())) return false;
  for (int r = 0; r <= c; ++r)
    if (last_row_start_[r] != (r < c ? rows.begin(r) : rows.end(c - 1))) return false;
  const int terms = c > 0 ? rows.end(c - 1) : 0;
  for (int t = 0; t < terms; ++t)
    if (last_row_point_[t] != rows.point(t) || last_row_coeff_[t] != rows.coeff(t)) return false;
  return true;
}

void LagrangeMultiplierSolver::rememberRows(const ConstraintRows& rows) {
  const int c = rows.rows(), terms = c > 0 ? rows.end(c - 1) : 0;
  last_row_start_.resize(c + 1);
  for (int r = 0; r < c; ++r) last_row_start_[r] = rows.begin(r);
  last_row_start_[c] = terms;
  last_row_point_.resize(terms);
  last_row_coeff_.resize(terms);
  for (int t = 0; t < terms; ++t) {
    last_row_point_[t] = rows.point(t);
    last_row_coeff_[t] = rows.coeff(t);
  }
}

void LagrangeMultiplierSolver::scatterForces(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse,
                                             VecX& a) {
  // a += M⁻¹ (Lᵀ λ): scatter the generalized constraint forces, one solve per touched body.
  const int n3 = 3 * problem.dof_points;
  force_.setZero(n3);
  for (int r = 0; r < rows.rows(); ++r) rows.addTransposed(r, lambda_[r], force_);
  // Internal DOFs coupled to the points by A (a rod's frames under an implicit step) follow too.
  inverse.addInternalResponse(force_, a);
  if (inverse.coupled()) {
    inverse.solveAll(force_);
    a.head(n3) += force_;
    return;
  }
  const auto& bodies = problem.bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!body_touched_[b]) continue;
    const int offset = 3 * bodies[b].offset(), size = 3 * bodies[b].pointCount();
    inverse.solveBlock(static_cast<int>(b), force_.segment(offset, size));
    a.segment(offset, size) += force_.segment(offset, size);
  }
}

void LagrangeMultiplierSolver::mapPointsToBodies(const ConstraintProblem& problem) {
  if (point_body_problem_ == &problem && point_body_revision_ == problem.layout_revision &&
      static_cast<int>(point_body_.size()) == problem.dof_points)
    return;
  point_body_.assign(problem.dof_points, 0);
  const auto& bodies = problem.bodies;
  for (std::size_t b = 0; b < bodies.size(); ++b)
    std::fill_n(point_body_.begin() + bodies[b].offset(), bodies[b].pointCount(), static_cast<int>(b));
  point_body_problem_ = &problem;
  point_body_revision_ = problem.layout_revision;
}

void LagrangeMultiplierSolver::solve(const ConstraintProblem& problem, const ConstraintRows& rows, const BlockInverse& inverse,
                                     VecX& a) {
  mapPointsToBodies(problem);
  const int c = rows.rows();
  const bool separable = inverse.sameOnEveryAxis() && !inverse.coupled();
  // W is the last call's when the operator (the same object, its revision) and the rows are,
  // within one step: the contact Newton may then go on from that call's factorization.
  // The rows' kinds too (last_kinds_, the last Newton call's, before warmStart writes this
  // call's): the equality block kept for the next call is that of the same equality rows.
  bool same_kinds = static_cast<int>(last_kinds_.size()) == c;
  for (int r = 0; same_kinds && r < c; ++r) same_kinds = last_kinds_[r] == rows.kind(r);
  const bool same_w = !separable && !step_began_ && last_call_newton_ && inverse.revision() >= 0 &&
                      &inverse == cached_inverse_ && inverse.revision() == cached_revision_ &&
                      cached_size_ == problem.state_size && same_kinds && sameRowsAsLastCall(rows);
  if (!same_w) ++newton_key_;
  step_began_ = false;
  last_call_newton_ = false;  // (set at the end of a call that solved by Newton)
  stats_ = Statistics();
  stats_.rows = c;
  stats_.columns = separable ? rows.anchors() : c;
  stats_.inequalities = rows.inequalityCount();
  // Contacts by Newton need W dense (contact_newton.hpp): kept dense up to newton_rows rows.
  const bool newton = stats_.inequalities > 0 && options_.contact_method == ContactMethod::kNewton &&
                      c <= options_.newton_rows;
  stats_.sparse = c > options_.sparse_above && !newton;
  // Row-sized buffers grow only (the contact rows change in number from step to step).
  c_ = c;
  if (rhs_.size() < c) {
    rhs_.resize(2 * c);
    diagonal_.resize(2 * c);
    lambda_.conservativeResize(2 * c);
  }

  // Equality rows alone through a band (a rod held along a channel: hundreds of rows, each on a
  // point or two): the augmented system's envelope LU, W neither formed nor factored.
  if (stats_.inequalities == 0 && !separable) {
    if (solveEqualitiesThroughBand(problem, rows, inverse, a)) {
      scatterForces(problem, rows, inverse, a);
      have_general_ = false;
      columns_ready_ = false;
      factored_last_call_ = false;
      have_factorization_ = false;
      last_factor_start_.clear();
      previous_index_.clear();
      return;
    }
    // Refused for a pivot <= 0: W dense, factored with pivoting (Eigen's LDLT), not the sparse way.
    if (equality_pivot_refused_) stats_.sparse = false;
  }

  // 1. Columns of M⁻¹ Lᵀ (per anchor or per row), kept or solved. Through an operator that mixes
  // the axes the columns are kept whole when the operator (its revision) and the rows did not
  // change since the last call: a linearized implicit step and its error estimate, or steps
  // that reuse their factorization, solve through the same A.
  const bool general_kept = !separable && have_general_ && options_.reuse && inverse.revision() >= 0 &&
                            &inverse == cached_inverse_ && inverse.revision() == cached_revision_ &&
                            cached_size_ == problem.state_size && sameRowsAsLastCall(rows);
  // With Newton (W dense) through an operator that mixes the axes but not the bodies, W may come
  // from A⁻¹'s blocks between the rows' points instead (point_inverse_blocks.hpp), kept while A
  // is. The capstan held reuses its step matrix for ~20 steps (bench_realtime): its contacts then
  // solve only for the few points they move onto. Taken when it would cost fewer multiply-adds
  // with nothing held, S a solve on the rows' bodies (a band: 9 per block of both sweeps and the
  // pivot, 9 g (2 r + 1) for g block rows of half bandwidth r; 63 per point otherwise; summed
  // over the bodies, which overstates a solve in a scene of many bodies) and m the rows'
  // distinct points:
  //   columns: c solves,                          c S;
  //   points:  3 per point,                       3 m S + 36 m c (Z) + 9 m² (H_m);
  // W's products (6 c²) are common. What is held only saves solves: the choice must not depend
  // on it, so that a run restored from a saved state takes the same path and repeats bit for bit. Measured (wall ms per simulated ms, columns against points):
  // the capstan (m ≈ 20 of 170 points, the matrix kept) 0.58 and 0.49; a rod of 100 nodes on a
  // table (a new matrix every solve, 3 m = 300 solves against c ≈ 600, S doubled by the frames)
  // 5.8 and 4.9; a 2 m bowel (3 m = 243 solves against c ≈ 390 on a spline's cheaper band)
  // 2.1 and 2.9 — which this model sends to the columns.
  //
  // Newton whose products with W go through A's band (BandDelassusProduct) needs W's entries only
  // for a dense LU step or Gauss–Seidel's smoothing: W is then formed when first asked for
  // (DeferredDelassus), and a solve whose steps all go through the band never forms it — O(c²
  // terms), most of a step of a rod lying on a table (bench_rod) before. What it needs then is
  // W's diagonal (ρ, the compliance): from A⁻¹'s blocks within the band or a few groups beyond
  // (Takahashi's equations, O(n R r) per body) for the rows whose points lie that near, as on a
  // thread against an obstacle or in a lumen — no solve per row or per point, which grew as c n —
  // and by a solve of its own for a row reaching farther (a self-contact; inverseBandCovers). W
  // formed late takes the columns or the point blocks.
  const bool deferred = newton && !separable && options_.newton_structured &&
                        band_product_.prepare(rows, inverse, problem, point_body_) && band_product_.cheaperThanDense();
  stats_.deferred = deferred;
  // On the same W as a deferred call that took its diagonal from the band (the estimate after the
  // step), that diagonal is this call's too: the same rows and A give the same bits.
  const bool diagonal_held = deferred && same_w && band_diagonal_held_;
  band_diagonal_held_ = false;
  const bool by_band = diagonal_held || (deferred && inverseBandCovers(problem, rows, inverse));
  if (diagonal_held) {
    stats_.far_rows = held_far_rows_;
    stats_.inverse_range = held_inverse_range_;
  }
  const bool by_points = !by_band && newton && !general_kept && choosePointBlocks(problem, rows, inverse);
  stats_.point_blocks = by_points;
  source_ = by_band ? DelassusSource::kInverseBand : by_points ? DelassusSource::kPointBlocks : DelassusSource::kColumns;
  if (general_kept)
    stats_.reused_columns = c;
  else if (source_ == DelassusSource::kColumns)
    prepareColumns(problem, rows, inverse, separable);
  columns_ready_ = general_kept || source_ == DelassusSource::kColumns;

  // 2. W = L M⁻¹ Lᵀ (lower triangle), dense or with the entries below round-off dropped —
  // unless every column was taken over from the same place and every row has the same factors
  // (anchor and direction) as in the last call: W is then the same matrix, already factored.
  bool unchanged = separable && have_factorization_ && stats_.reused_columns == stats_.columns &&
                   stats_.sparse == last_sparse_ && c + 1 == static_cast<int>(last_factor_start_.size());
  for (int i = 0; unchanged && i < stats_.columns; ++i) unchanged = current_[i].from == i;
  unchanged = unchanged || (general_kept && !w_unformed_);
  for (int r = 0; unchanged && r <= c; ++r) unchanged = last_factor_start_[r] == (r < c ? rows.factorBegin(r) : rows.factorEnd(c - 1));
  const int factors = c > 0 ? rows.factorEnd(c - 1) : 0;
  for (int f = 0; unchanged && f < factors; ++f)
    unchanged = last_factor_anchor_[f] == rows.factorAnchor(f) && last_factor_direction_[f] == rows.factorDirection(f);
  // Contact rows through an operator that mixes the axes (an implicit step matrix): projected
  // Gauss–Seidel on the factored form (FactoredDelassus), W not assembled — only its diagonal.
  const bool factored_form = !newton && stats_.inequalities > 0 && !separable && !inverse.coupled() &&
                             (options_.contact_form == ContactForm::kAuto ? factoredFormIsCheaper(problem, rows)
                                                                           : options_.contact_form == ContactForm::kFactored);
  if (factored_form) {
    for (int r = 0; r < c; ++r) diagonal_[r] = generalEntry(problem, rows, r, r);
  } else if (deferred && !unchanged) {
    if (!diagonal_held) {
      if (by_band) computeInverseBands(problem, rows, inverse);
      for (int r = 0; r < c; ++r) diagonal_[r] = diagonalEntry(problem, rows, r);
    }
    stats_.held = diagonal_held;
    band_diagonal_held_ = by_band;
    held_far_rows_ = stats_.far_rows;
    held_inverse_range_ = stats_.inverse_range;
    w_unformed_ = true;
  } else if (!unchanged) {
    if (stats_.sparse) {
      sparse_->triplets.clear();
    } else {
      if (w_.rows() < c) w_.resize(c, c);  // grows only (entries r, k < c are used)
    }
    if (separable) {
      assembleSeparable(problem, rows);
    } else if (by_points) {
      assembleFromPointBlocks(rows);
    } else {
      assembleGeneral(problem, rows);
    }
    stats_.reassembled = true;
    last_nonzeros_ = stats_.nonzeros;
    w_unformed_ = false;
  } else {
    stats_.nonzeros = last_nonzeros_;
  }

  // 3. E − L A_t.
  for (int r = 0; r < c; ++r) rhs_[r] = rows.rhs(r) - rows.dot(r, a);

  // 4. λ = W⁻¹ (E − L A_t), or with contact rows the projected Gauss–Seidel solution.
  if (newton) {
    solveWithNewton(problem, rows, inverse, deferred);
    factored_last_call_ = false;
    last_call_newton_ = !separable;
  } else if (factored_form) {
    FactoredDelassus w{*this, problem, rows, u_};
    solveWithContacts(rows, w);
    factored_last_call_ = false;
  } else if (stats_.inequalities > 0 && !stats_.sparse) {
    DenseDelassus w{*this};  // diagonal_ holds W_rr since W's assembly (this call or an identical last one)
    solveWithContacts(rows, w);
    factored_last_call_ = false;
  } else if (stats_.inequalities > 0) {
    buildAdjacency(c);  // diagonal_ holds W_rr since W's assembly (this call or an identical last one)
    AssembledDelassus w{*this};
    solveWithContacts(rows, w);
    factored_last_call_ = false;
  } else if (unchanged && factored_last_call_) {
    if (stats_.sparse) {
      sparse_->solve(rhs_.head(c), lambda_.head(c));
    } else {
      lambda_.head(c) = ldlt_.solve(rhs_.head(c));
    }
  } else {
    factorAndSolve();
    factored_last_call_ = true;
  }
  if (stats_.inequalities > 0)
    tally_.add(stats_.converged, stats_.fell_back,
               stats_.newton_iterations > 0 ? stats_.newton_iterations : stats_.sweeps,
               stats_.threshold > 0.0 ? stats_.residual / stats_.threshold : 0.0, stats_.chord_steps);
  // Remember the structure W was built from (mass operator only: nothing else is kept).
  have_factorization_ = separable && lambda_.head(c).allFinite();
  last_sparse_ = stats_.sparse;
  last_factor_start_.resize(c + 1);
  for (int r = 0; r < c; ++r) last_factor_start_[r] = rows.factorBegin(r);
  last_factor_start_[c] = factors;
  last_factor_anchor_.resize(factors);
  last_factor_direction_.resize(factors);
  for (int f = 0; f < factors; ++f) {
    last_factor_anchor_[f] = rows.factorAnchor(f);
    last_factor_direction_[f] = rows.factorDirection(f);
  }

  // 5. A = A_t + M⁻¹ (Lᵀ λ). Through an operator that mixes the axes, one column y_r = A⁻¹ l_r
  // per row is at hand: A⁻¹ Lᵀ λ = Σ_r λ_r y_r costs 3 multiply-adds per point and row, a band
  // solve ~60 per point (3 × 3 blocks, 3 block diagonals each side): the sum is cheaper up to
  // ~20 rows (kColumnSumRows).
  constexpr int kColumnSumRows = 16;
  if (factored_form) {
    a.head(u_.size()) += u_;  // kept by the projected Gauss–Seidel sweeps
  } else if (!separable && !inverse.coupled() && c <= kColumnSumRows && source_ == DelassusSource::kColumns) {  // (the columns were solved)
    const auto& bodies = problem.bodies;
    for (int r = 0; r < c; ++r) {
      const Column& col = current_[r];
      for (std::size_t seg = 0; seg < col.bodies.size(); ++seg) {
        const BodyBlock& body = bodies[col.bodies[seg]];
        const int size = 3 * body.pointCount();
        a.segment(3 * body.offset(), size) += lambda_[r] * col.y.segment(col.starts[seg], size);
      }
    }
    if (problem.internal_dofs) {  // the internal DOFs' part of A⁻¹ Lᵀ λ (a rod's frames)
      force_.setZero(3 * problem.dof_points);
      for (int r = 0; r < c; ++r) rows.addTransposed(r, lambda_[r], force_);
      inverse.addInternalResponse(force_, a);
    }
  } else {
    scatterForces(problem, rows, inverse, a);
  }

  // Keep this call's columns for the next one (mass operator only).
  if (separable) {
    std::swap(current_, previous_);
    const int count = rows.anchors();
    previous_index_.clear();
    for (int i = 0; i < count; ++i) {
      previous_[i].taken = false;
      previous_index_.emplace_back(previous_[i].hash, i);
    }
    for (std::size_t i = count; i < previous_.size(); ++i) previous_[i].taken = true;  // stale
    std::sort(previous_index_.begin(), previous_index_.end());
    cached_inverse_ = &inverse;
    cached_revision_ = inverse.revision();
    cached_size_ = problem.state_size;
  } else {
    previous_index_.clear();
    have_general_ = lambda_.head(c).allFinite() && inverse.revision() >= 0 && columns_ready_;  // (none: no columns kept)
    if (!general_kept) rememberRows(rows);
    cached_inverse_ = &inverse;
    cached_revision_ = inverse.revision();
    cached_size_ = problem.state_size;
  }
}

}  // namespace filum::constraints
