#include "filum/geometry/knot_insertion.hpp"

#include <algorithm>
#include <array>
#include <sstream>
#include <stdexcept>
#include <string>

#include "filum/geometry/knot_vector.hpp"

namespace filum::geometry {

namespace {

void checkInsertable(int d, int n, const std::vector<double>& knots, double u, int copies, const char* what) {
  const double start = knots[d], end = knots[n];
  if (!(u > start && u < end)) {
    std::ostringstream m;
    m.precision(17);
    m << what << ": knot " << u << " is not strictly inside the domain (" << start << ", " << end << ")";
    throw std::invalid_argument(m.str());
  }
  const int multiplicity = knotMultiplicity(knots, u) + copies;
  if (multiplicity > d + 1) {
    std::ostringstream m;
    m.precision(17);
    m << what << ": knot " << u << " would get multiplicity " << multiplicity << " > degree + 1 = " << d + 1;
    throw std::invalid_argument(m.str());
  }
}

/// α^d_{μ−d+k, row} for k = 0..d ([Lenoir talk 2008] recurrence) into alpha[k]; returns μ. Entries with
/// μ − d + k < 0 (no such B-spline: t̃_row left of t_d on an unclamped vector) stay 0; the others
/// only depend on entries of index >= their own, so they are computed exactly as if the knot
/// vector extended further left.
int osloRow(int d, const std::vector<double>& t, const std::vector<double>& refined, int row,
            std::array<double, BasisRow::kMaxSupport>& alpha) {
  // μ: t_μ <= t̃_row < t_{μ+1}. t̃_row <= t̃_{ñ−1} < t̃_ñ = t_n (the domain end is simple and
  // unchanged), so μ <= n − 1.
  const int mu = static_cast<int>(std::upper_bound(t.begin(), t.end(), refined[row]) - t.begin()) - 1;
  alpha.fill(0.0);
  alpha[d] = 1.0;  // α^0_{μ} = 1; alpha[k] holds α_{μ−d+k}
  for (int r = 1; r <= d; ++r) {
    const double x = refined[row + r];  // t̃_{j+r}
    // α^r_i for i = μ−r..μ, increasing i: reads old α_i and α_{i+1} before overwriting α_i.
    for (int i = std::max(mu - r, 0); i <= mu; ++i) {
      const int k = i - (mu - d);
      double value = 0.0;
      if (i >= mu - r + 1) value += (x - t[i]) / (t[i + r] - t[i]) * alpha[k];
      if (i + 1 <= mu) value += (t[i + r + 1] - x) / (t[i + r + 1] - t[i + 1]) * alpha[k + 1];
      alpha[k] = value;
    }
  }
  return mu;
}

/// Rows of the refinement that are plain copies. If t̃_{j+1..j+d} = t_{j+1..j+d} then q̃_j = q_j (the
/// blossom of the same arguments, de Boor), which holds for every row j <= copied_before − 1
/// whose fine knots t̃_j..t̃_{j+d+1} precede the first inserted knot; likewise q̃_j = q_{j−k} for
/// the rows j >= copied_after whose fine knots all lie in the unchanged tail (k = ñ − n).
struct CopiedRows {
  int before;  // rows 0..before−1 are q̃_j = q_j
  int after;   // rows after..ñ−1 are q̃_j = q_{j−k}
};

CopiedRows copiedRows(int d, const std::vector<double>& t, const std::vector<double>& refined) {
  const int coarse = static_cast<int>(t.size()), fine = static_cast<int>(refined.size());
  int same_head = 0;  // t̃_i = t_i for i < same_head
  while (same_head < coarse && refined[same_head] == t[same_head]) ++same_head;
  int same_tail = 0;  // t̃_{fine−1−i} = t_{coarse−1−i} for i < same_tail
  while (same_tail < coarse && refined[fine - 1 - same_tail] == t[coarse - 1 - same_tail]) ++same_tail;
  const int refined_count = fine - d - 1;
  // Row j copies when j + d + 1 < same_head, resp. j >= fine − same_tail.
  const int before = std::clamp(same_head - d - 1, 0, refined_count);
  const int after = std::clamp(fine - same_tail, before, refined_count);
  return {before, after};
}

}  // namespace

BSplineCurve insertKnot(const BSplineCurve& curve, double u, int times) {
  validateBSplineCurve(curve, "insertKnot");
  if (times < 1) throw std::invalid_argument("insertKnot: times must be >= 1, got " + std::to_string(times));
  checkInsertable(curve.degree, curve.controlPointCount(), curve.knots, u, times, "insertKnot");
  BSplineCurve out = curve;
  const int d = curve.degree;
  for (int pass = 0; pass < times; ++pass) {
    const std::vector<double>& t = out.knots;
    const int n = out.controlPointCount();
    const int k = findKnotSpan(d, n, t, u);  // t_k <= u < t_{k+1}
    Points q(n + 1, 3);
    q.topRows(k - d + 1) = out.control_points.topRows(k - d + 1);
    for (int i = k - d + 1; i <= k; ++i) {
      const double alpha = (u - t[i]) / (t[i + d] - t[i]);  // α_i = (u − t_i)/(t_{i+d} − t_i)
      q.row(i) = alpha * out.control_points.row(i) + (1.0 - alpha) * out.control_points.row(i - 1);
    }
    q.bottomRows(n - k) = out.control_points.bottomRows(n - k);  // q̃_i = q_{i−1}, i >= k + 1
    out.control_points = std::move(q);
    out.knots.insert(out.knots.begin() + k + 1, u);
  }
  return out;
}

std::vector<double> refinedKnotVector(int degree, const std::vector<double>& knots,
                                      const std::vector<double>& new_knots) {
  const long coarse_count = static_cast<long>(knots.size()) - degree - 1;
  validateKnotVector(degree, static_cast<int>(coarse_count), knots, "insertKnots");
  std::vector<double> sorted = new_knots;
  std::sort(sorted.begin(), sorted.end());
  for (std::size_t i = 0; i < sorted.size();) {
    std::size_t j = i;
    while (j < sorted.size() && sorted[j] == sorted[i]) ++j;
    checkInsertable(degree, static_cast<int>(coarse_count), knots, sorted[i], static_cast<int>(j - i), "insertKnots");
    i = j;
  }
  std::vector<double> refined;
  refined.reserve(knots.size() + sorted.size());
  std::merge(knots.begin(), knots.end(), sorted.begin(), sorted.end(), std::back_inserter(refined));
  return refined;
}

BSplineCurve insertKnots(const BSplineCurve& curve, const std::vector<double>& new_knots) {
  validateBSplineCurve(curve, "insertKnots");
  const int d = curve.degree;
  BSplineCurve out;
  out.degree = d;
  out.knots = refinedKnotVector(d, curve.knots, new_knots);
  const int refined_count = static_cast<int>(out.knots.size()) - d - 1;
  out.control_points.resize(refined_count, 3);
  const CopiedRows copied = copiedRows(d, curve.knots, out.knots);
  out.control_points.topRows(copied.before) = curve.control_points.topRows(copied.before);
  out.control_points.bottomRows(refined_count - copied.after) =
      curve.control_points.bottomRows(refined_count - copied.after);
  std::array<double, BasisRow::kMaxSupport> alpha;
  for (int j = copied.before; j < copied.after; ++j) {
    const int mu = osloRow(d, curve.knots, out.knots, j, alpha);
    // q̃_j = Σ_i α^d_{i,j} q_i
    Eigen::RowVector3d sum = Eigen::RowVector3d::Zero();
    for (int k = std::max(0, d - mu); k <= d; ++k) sum += alpha[k] * curve.control_points.row(mu - d + k);
    out.control_points.row(j) = sum;
  }
  return out;
}

SparseMatrix knotInsertionMatrix(int degree, const std::vector<double>& knots,
                                 const std::vector<double>& refined_knots) {
  const int d = degree;
  const int n = static_cast<int>(knots.size()) - d - 1;
  validateKnotVector(d, n, knots, "knotInsertionMatrix (coarse knots)");
  const int refined_count = static_cast<int>(refined_knots.size()) - d - 1;
  validateKnotVector(d, refined_count, refined_knots, "knotInsertionMatrix (refined knots)");
  if (!std::includes(refined_knots.begin(), refined_knots.end(), knots.begin(), knots.end()) ||
      refined_knots[d] != knots[d] || refined_knots[refined_count] != knots[n])
    throw std::invalid_argument(
        "knotInsertionMatrix: the refined knots must contain the coarse ones and keep the domain [t_d, t_n]");
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(static_cast<std::size_t>(refined_count) * (d + 1));
  std::array<double, BasisRow::kMaxSupport> alpha;
  const CopiedRows copied = copiedRows(d, knots, refined_knots);
  const int shift = refined_count - n;
  for (int j = 0; j < refined_count; ++j) {
    if (j < copied.before || j >= copied.after) {
      entries.emplace_back(j, j < copied.before ? j : j - shift, 1.0);
      continue;
    }
    const int mu = osloRow(d, knots, refined_knots, j, alpha);
    for (int k = std::max(0, d - mu); k <= d; ++k)
      if (alpha[k] != 0.0) entries.emplace_back(j, mu - d + k, alpha[k]);
  }
  SparseMatrix A(refined_count, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

}  // namespace filum::geometry
