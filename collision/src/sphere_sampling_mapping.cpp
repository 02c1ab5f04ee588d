#include "filum/collision/sphere_sampling_mapping.hpp"

#include <algorithm>
#include <cmath>
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

SphereSamplingMapping::SphereSamplingMapping(const geometry::SplineBasis& basis, double spacing)
    : basis_(basis.clone()), spacing_(spacing) {
  if (!(spacing > 0.0) || !std::isfinite(spacing))
    throw std::invalid_argument("SphereSamplingMapping: the spacing must be positive and finite");
  // The arc-length table's abscissas (kTablePerPiece per polynomial piece) and the basis
  // derivatives at them and at the Gauss nodes of every table interval: fixed, so that each
  // resample only forms P'(s) = Σ b'_i(s) q_i.
  const std::vector<double> pieces = basis.breakpoints();
  auto derivative = [&](double s) {
    geometry::BasisRow row;
    basis_->evaluate(s, row);
    Derivative d;
    d.first = row.first;
    d.count = row.count;
    d.d1 = row.d1;
    return d;
  };
  for (std::size_t piece = 0; piece + 1 < pieces.size(); ++piece) {
    if (!(pieces[piece + 1] > pieces[piece])) continue;
    for (int j = (table_s_.empty() ? 0 : 1); j <= kTablePerPiece; ++j) {
      const double s = pieces[piece] + (pieces[piece + 1] - pieces[piece]) * j / kTablePerPiece;
      if (!table_s_.empty()) {
        const double a = table_s_.back();
        for (int g = 0; g < kGaussNodes; ++g) gauss_.push_back(derivative(a + (s - a) * kGaussX[g]));
      }
      table_s_.push_back(s);
      table_derivative_.push_back(derivative(s));
    }
  }
  table_length_.resize(table_s_.size());
  table_speed_.resize(table_s_.size());
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
  // unless the curve nearly stops, P' ≈ 0, where it falls back towards the chord length).
  const int entries = static_cast<int>(table_s_.size());
  table_length_[0] = 0.0;
  table_speed_[0] = speed(table_derivative_[0]);
  for (int j = 1; j < entries; ++j) {
    double integral = 0.0;
    for (int g = 0; g < kGaussNodes; ++g) integral += kGaussW[g] * speed(gauss_[(j - 1) * kGaussNodes + g]);
    table_length_[j] = table_length_[j - 1] + integral * (table_s_[j] - table_s_[j - 1]);
    table_speed_[j] = speed(table_derivative_[j]);
  }
  length_ = table_length_.back();
  // K = ⌈L / h⌉ + 1 centres, spacing L / (K − 1) <= h.
  const double wanted = std::ceil(length_ / spacing_ - 1e-9) + 1.0;
  if (!(wanted <= 4.0 * kMaxSpheresPerThread))
    throw std::runtime_error("a thread of length " + std::to_string(length_) + " m would need " + std::to_string(wanted) +
                             " spheres of spacing " + std::to_string(spacing_) + " m (at most " +
                             std::to_string(4 * kMaxSpheresPerThread) + ")");
  const int count = std::max(2, static_cast<int>(wanted));
  actual_spacing_ = length_ / (count - 1);

  // ℓ ↦ s by cubic Hermite interpolation of the inverse on each table interval, ds/dℓ = 1/|P'|:
  // error O(Δs⁴), about 1e-7 of the spacing for curves bent to the radius of a piece.
  abscissas_.resize(count);
  rows_.resize(count);
  int j = 0;
  for (int k = 0; k < count; ++k) {
    const double target = k * actual_spacing_;
    while (j + 2 < entries && table_length_[j + 1] < target) ++j;
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
    abscissas_[k] = s;
  }
  abscissas_.front() = 0.0;
  abscissas_.back() = 1.0;
  for (int k = 0; k < count; ++k) basis_->evaluate(abscissas_[k], rows_[k]);
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

PointWeights SphereSamplingMapping::pointWeights(int k, double t) const {
  PointWeights w;
  auto add = [&w](const geometry::BasisRow& r, double scale) {
    if (scale == 0.0) return;
    for (int j = 0; j < r.count; ++j) {
      const int p = r.first + j;
      int slot = 0;
      while (slot < w.count && w.point[slot] != p) ++slot;
      if (slot == w.count) {
        w.point[w.count] = p;
        w.weight[w.count++] = 0.0;
      }
      w.weight[slot] += scale * r.value[j];
    }
  };
  if (k + 1 >= outputCount() || t <= 0.0) {
    add(rows_[k], 1.0);
  } else {
    add(rows_[k], 1.0 - t);
    add(rows_[k + 1], t);
  }
  return w;
}

}  // namespace filum::collision
