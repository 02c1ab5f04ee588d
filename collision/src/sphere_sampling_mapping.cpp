#include "filum/collision/sphere_sampling_mapping.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <limits>
#include <stdexcept>


namespace filum::collision {

namespace {

// 4-point Gauss–Legendre on [0, 1]: nodes and weights (exact for polynomials of degree <= 7).
constexpr int kGaussNodes = 4;
constexpr double kGaussX[kGaussNodes] = {0.0694318442029737, 0.3300094782075719, 0.6699905217924281,
                                         0.9305681557970263};
constexpr double kGaussW[kGaussNodes] = {0.1739274225687269, 0.3260725774312731, 0.3260725774312731,
                                         0.1739274225687269};
constexpr int kTablePerPiece = 8;  // table entries per polynomial piece of the basis

}  // namespace

SphereSamplingMapping::SphereSamplingMapping(const CurveBasis& basis, double spacing)
    : basis_(basis.clone()), spacing_(spacing), strands_(filum::strands(basis)) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw std::invalid_argument("SphereSamplingMapping: the spacing must be positive and finite");
  // The arc-length table's abscissas (kTablePerPiece per polynomial piece), strand by strand,
  // and the basis derivatives at them and at the Gauss nodes of every table interval: fixed, so
  // that each resample only forms P'(s) = Σ b'_i(s) q_i. A strand's last entry is its own end
  // (evaluated from the left at a cut), the next strand starts with an entry of its own.
  const std::vector<double> pieces = basis.breakpoints();
  auto derivative = [&](double s, bool from_left) {
    geometry::BasisRow row;
    from_left ? basis_->evaluateFromLeft(s, row) : basis_->evaluate(s, row);
    return Derivative{row.first, row.count, row.d1};
  };
  for (const Strand& strand : strands_) {
    strand_table_begin_.push_back(static_cast<int>(table_s_.size()));
    for (std::size_t piece = 0; piece + 1 < pieces.size(); ++piece) {
      if (!(pieces[piece] >= strand.begin && pieces[piece + 1] <= strand.end && pieces[piece + 1] > pieces[piece]))
        continue;
      const bool first = static_cast<int>(table_s_.size()) == strand_table_begin_.back();
      for (int j = first ? 0 : 1; j <= kTablePerPiece; ++j) {
        const double s = pieces[piece] + (pieces[piece + 1] - pieces[piece]) * j / kTablePerPiece;
        const bool strand_end = j == kTablePerPiece && pieces[piece + 1] >= strand.end;
        if (!first || j > 0) {
          const double a = table_s_.back();
          for (int g = 0; g < kGaussNodes; ++g) gauss_.push_back(derivative(a + (s - a) * kGaussX[g], false));
        } else {
          gauss_.resize(gauss_.size() + kGaussNodes);  // no interval ends at a strand's first entry
        }
        table_s_.push_back(s);
        table_derivative_.push_back(derivative(strand_end ? strand.end : s, strand_end));
      }
    }
  }
  strand_table_begin_.push_back(static_cast<int>(table_s_.size()));
  table_length_.resize(table_s_.size());
  table_speed_.resize(table_s_.size());
  strand_spacing_.resize(strands_.size());
}

void SphereSamplingMapping::resample(ConstPointsRef q) {
  // |P'(s)| from a row of basis derivatives.
  auto speed = [&q](const Derivative& d) {
    Vec3 tangent = Vec3::Zero();
    for (int i = 0; i < d.count; ++i) tangent += d.d1[i] * q.row(d.first + i).transpose();
    return tangent.norm();
  };
  // Arc length L(s_j) = Σ ∫ |P'| over the table intervals, 4-point Gauss–Legendre on each (an
  // interval is 1/8 of a polynomial piece, where |P'| is smooth: relative error far below 1e-8
  // unless the curve nearly stops, P' ≈ 0, where it falls back towards the chord length),
  // from 0 at the start of each strand.
  const int strand_count = static_cast<int>(strands_.size());
  length_ = 0.0;
  double wanted_total = 0.0;
  for (int t = 0; t < strand_count; ++t) {
    const int begin = strand_table_begin_[t], end = strand_table_begin_[t + 1];
    table_length_[begin] = 0.0;
    table_speed_[begin] = speed(table_derivative_[begin]);
    for (int j = begin + 1; j < end; ++j) {
      double integral = 0.0;
      for (int g = 0; g < kGaussNodes; ++g) integral += kGaussW[g] * speed(gauss_[j * kGaussNodes + g]);
      table_length_[j] = table_length_[j - 1] + integral * (table_s_[j] - table_s_[j - 1]);
      table_speed_[j] = speed(table_derivative_[j]);
    }
    length_ += table_length_[end - 1];
    wanted_total += centresOnStrand(t);
  }
  if (!(wanted_total <= 4.0 * kMaxSpheresPerThread))
    throw std::runtime_error("a thread of length " + std::to_string(length_) + " m would need " +
                             std::to_string(wanted_total) + " spheres of spacing " + std::to_string(spacing_) +
                             " m (at most " + std::to_string(4 * kMaxSpheresPerThread) + ")");
  const int total = static_cast<int>(wanted_total);
  abscissas_.resize(total);
  rows_.resize(total);
  strand_of_.resize(total);
  left_limit_.resize(total);
  arc_of_.resize(total);
  actual_spacing_ = 0.0;
  int k = 0;
  double base = 0.0;
  for (int t = 0; t < strand_count; ++t) {
    const int count = sampleStrand(t, k, base);
    actual_spacing_ = std::max(actual_spacing_, strand_spacing_[t]);
    base += table_length_[strand_table_begin_[t + 1] - 1];
    k += count;
  }
}

double SphereSamplingMapping::centresOnStrand(int t) const {
  const int begin = strand_table_begin_[t], end = strand_table_begin_[t + 1];
  const double length = table_length_[end - 1];
  // A polyline (degree 1: a rod's centre line) bends only at its vertices, and a vertex between
  // two centres pokes out of their spheres towards the outside of the bend, by up to
  // (h/2) sin(θ/2) for a turn θ — a tenth of the radius at 13° with h = 2r. So its centres are
  // placed piece by piece (samplePolylineStrand), ⌈ℓ_p / h⌉ on each piece p, and every vertex is
  // a centre however unequal the pieces.
  if (isPolyline(t)) {
    double count = 1.0;
    for (int j = begin; j + kTablePerPiece < end; j += kTablePerPiece) count += centresOnPiece(j);
    return count;
  }
  // K = ⌈L / h⌉ + 1 centres on the strand, spacing L / (K − 1) <= h (in doubles: the caller checks
  // the total against the limit before anything is cast or allocated).
  return std::max(2.0, std::ceil(length / spacing_ - 1e-9) + 1.0);
}

bool SphereSamplingMapping::isPolyline(int t) const {
  return basis_->degree() == 1 && strand_table_begin_[t + 1] - strand_table_begin_[t] - 1 >= kTablePerPiece;
}

double SphereSamplingMapping::centresOnPiece(int j) const {
  return std::max(1.0, std::ceil((table_length_[j + kTablePerPiece] - table_length_[j]) / spacing_ - 1e-9));
}

void SphereSamplingMapping::samplePolylineStrand(int t, int first, int count) {
  // Piece by piece: a linear piece has |P'| constant, so equal steps of s are equal steps of arc
  // length on it; the vertices (the table entries at the pieces' ends) are centres, the last one
  // the strand's end.
  const int begin = strand_table_begin_[t], end = strand_table_begin_[t + 1];
  strand_spacing_[t] = 0.0;
  int i = first;
  for (int a = begin; a + kTablePerPiece < end; a += kTablePerPiece) {
    const int b = a + kTablePerPiece;
    const int m = static_cast<int>(centresOnPiece(a));
    for (int k = 0; k < m; ++k, ++i) {
      const double u = static_cast<double>(k) / m;
      abscissas_[i] = table_s_[a] + u * (table_s_[b] - table_s_[a]);
      arc_of_[i] = table_length_[a] + u * (table_length_[b] - table_length_[a]);
    }
    strand_spacing_[t] = std::max(strand_spacing_[t], (table_length_[b] - table_length_[a]) / m);
  }
  abscissas_[i] = table_s_[end - 1];
  arc_of_[i] = table_length_[end - 1];
  assert(i == first + count - 1 && "samplePolylineStrand: the count is centresOnStrand's");
  (void)count;
}

int SphereSamplingMapping::sampleStrand(int t, int first, double base) {
  const int begin = strand_table_begin_[t], end = strand_table_begin_[t + 1];
  const double length = table_length_[end - 1];
  const int count = static_cast<int>(centresOnStrand(t));  // checked against the limit by resample
  const bool polyline = isPolyline(t);
  if (polyline) samplePolylineStrand(t, first, count);
  else strand_spacing_[t] = length / (count - 1);
  // ℓ ↦ s by cubic Hermite interpolation of the inverse on each table interval, ds/dℓ = 1/|P'|:
  // error O(Δs⁴), about 1e-7 of the spacing for curves bent to the radius of a piece.
  int j = begin;
  for (int i = 0; i < count && !polyline; ++i) {
    const double target = i * strand_spacing_[t];
    while (j + 2 < end && table_length_[j + 1] < target) ++j;
    const double l0 = table_length_[j], l1 = table_length_[j + 1], dl = l1 - l0;
    const double s0 = table_s_[j], s1 = table_s_[j + 1];
    double s = s0;
    if (dl > 0.0) {
      const double secant = (s1 - s0) / dl;  // where P' = 0 the slope is taken as the secant
      const double m0 = table_speed_[j] > 0.0 ? 1.0 / table_speed_[j] : secant;
      const double m1 = table_speed_[j + 1] > 0.0 ? 1.0 / table_speed_[j + 1] : secant;
      const double u = std::clamp((target - l0) / dl, 0.0, 1.0), u2 = u * u, u3 = u2 * u;
      s = (2 * u3 - 3 * u2 + 1) * s0 + (u3 - 2 * u2 + u) * dl * m0 + (-2 * u3 + 3 * u2) * s1 + (u3 - u2) * dl * m1;
      s = std::clamp(s, s0, s1);
    }
    abscissas_[first + i] = s;
  }
  abscissas_[first] = strands_[t].begin;
  abscissas_[first + count - 1] = strands_[t].end;
  for (int i = 0; i < count; ++i) {
    evaluateOnStrand(*basis_, strands_[t], abscissas_[first + i], rows_[first + i]);
    left_limit_[first + i] = abscissas_[first + i] >= strands_[t].end;  // as evaluateOnStrand decides
    strand_of_[first + i] = t;
    arc_of_[first + i] = base + (polyline ? arc_of_[first + i] : i * strand_spacing_[t]);
  }
  return count;
}

double SphereSamplingMapping::chordDistanceBound(int k, int l) const {
  // The chords' points are within one spacing after their first centres: (|k − l| + 1) h on
  // one strand.
  return std::abs(arc_of_[k] - arc_of_[l]) +
         std::max(strand_spacing_[strand_of_[k]], strand_spacing_[strand_of_[l]]);
}

double SphereSamplingMapping::arcDistance(int k, double t, int l, double u) const {
  // A chord's own length: a polyline's chords differ from piece to piece.
  const auto chord = [this](int c) {
    return basis_->degree() == 1 ? arc_of_[c + 1] - arc_of_[c] : strand_spacing_[strand_of_[c]];
  };
  const double a = arc_of_[k] + (joinsNext(k) ? t * chord(k) : 0.0);
  const double b = arc_of_[l] + (joinsNext(l) ? u * chord(l) : 0.0);
  return std::abs(a - b);
}

void SphereSamplingMapping::apply(ConstPointsRef in, PointsRef out) const {
  // x_k = Σ_j b_{first+j}(s_k) q_{first+j}
  for (int k = 0; k < outputCount(); ++k) {
    const geometry::BasisRow& r = rows_[k];
    Vec3 x = Vec3::Zero();
    for (int j = 0; j < r.count; ++j) x += r.value[j] * in.row(r.first + j).transpose();
    out.row(k) = x.transpose();
  }
}

void SphereSamplingMapping::applyJ(ConstPointsRef, ConstPointsRef v_in, PointsRef v_out) const {
  // The mapping is linear between resamplings: v_k = Σ_j b_j(s_k) q̇_j.
  for (int k = 0; k < outputCount(); ++k) {
    const geometry::BasisRow& r = rows_[k];
    Vec3 v = Vec3::Zero();
    for (int j = 0; j < r.count; ++j) v += r.value[j] * v_in.row(r.first + j).transpose();
    v_out.row(k) = v.transpose();
  }
}

void SphereSamplingMapping::applyJT(ConstPointsRef, ConstPointsRef f_out, PointsRef f_in) const {
  // Q_i += Σ_k b_i(s_k) F_k
  for (int k = 0; k < outputCount(); ++k) {
    const geometry::BasisRow& r = rows_[k];
    for (int j = 0; j < r.count; ++j) f_in.row(r.first + j) += r.value[j] * f_out.row(k);
  }
}

SparseMatrix SphereSamplingMapping::jacobian(ConstPointsRef) const {
  // J = W ⊗ I₃, coordinates interleaved (x y z per point).
  Triplets entries;
  for (int k = 0; k < outputCount(); ++k) {
    const geometry::BasisRow& r = rows_[k];
    for (int j = 0; j < r.count; ++j)
      for (int c = 0; c < 3; ++c) entries.emplace_back(3 * k + c, 3 * (r.first + j) + c, r.value[j]);
  }
  SparseMatrix J(3 * outputCount(), 3 * inputCount());
  J.setFromTriplets(entries.begin(), entries.end());
  return J;
}

BodyPoint SphereSamplingMapping::chordPoint(const CurveBody& body, int k, double t) const {
  // A strand's last centre was evaluated from the left (evaluateOnStrand): its point says so, so
  // that it stays that strand's end point if the body's layout changes.
  BodyPoint point;
  if (!joinsNext(k) || t <= 0.0)
    point.attach(body, abscissas_[k], rows_[k], left_limit_[k]);
  else
    point.attachChord(body, abscissas_[k], rows_[k], abscissas_[k + 1], rows_[k + 1], t, left_limit_[k],
                      left_limit_[k + 1]);
  return point;
}

}  // namespace filum::collision
