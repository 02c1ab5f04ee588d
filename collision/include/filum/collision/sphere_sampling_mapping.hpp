// SphereSamplingMapping: the collision side of a spline — K sphere centres at (near) equal
// curvilinear spacing along P(s) = Σ_i b_i(s) q_i (paper §3: "spheres are created by a sampling
// along the curve spline"; [Lenoir talk 2008]: "dynamic distribution (curvilinear distance)").
//
// resample(q) places the centres at the abscissas s_k with L(s_k) = k L / (K − 1), L the arc
// length of the current curve, and K = ⌈L / h⌉ + 1 for the target spacing h (for a polyline, a
// rod's centre line, K − 1 is a multiple of its pieces, so that its vertices are centres): as the thread stretches, spheres are added so that the spacing never exceeds
// h (and neighbouring spheres of radius r >= h keep overlapping — no gaps a thread could slip
// through). Between two resamplings the abscissas are fixed and the mapping is linear:
//   x_k = P(s_k) = Σ_i b_i(s_k) q_i,  J = W ⊗ I₃,  W_ki = b_i(s_k),
// so forces F_k at the centres go up to the control points as Q_i += Σ_k b_i(s_k) F_k (applyJT),
// and a point of the chord between centres k and k+1, x = (1 − t) x_k + t x_{k+1}, is the
// BodyPoint whose row is (1 − t) W_k + t W_{k+1} (chordPoint): forces at contacts go up through it.
//
// A cut curve (CurveBasis::cuts) is sampled strand by strand: each strand has its own centres,
// from its first end to its last, at its own spacing L_t / (K_t − 1) <= h (a polyline's strand
// piece by piece, ⌈ℓ_p / h⌉ chords on each piece p: its spacing is its longest chord), and no chord
// joins the last centre of a strand to the first of the next (joinsNext).
//
// Resampling runs at every step, so it is built for speed from fixed tables: L(s) on 8 table
// intervals per polynomial piece of the basis by 4-point Gauss–Legendre with the basis
// derivatives at the nodes precomputed (each step only forms P'(s) = Σ b'_i q_i there), and
// s(ℓ) by cubic Hermite interpolation with ds/dℓ = 1/|P'|. (geometry::ArcLengthParameterization,
// adaptive and exact to round-off, costs ten times as much per step: the tests check the two
// agree.)
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "filum/core/body_point.hpp"
#include "filum/core/mapping.hpp"
#include "filum/geometry/spline_basis.hpp"

namespace filum::collision {

/// Spheres along one thread, at most (checked on the rest length when a scene is loaded): the
/// broad and narrow phases visit every sphere at every step, and 1e6 is 1000 times the spheres
/// of the reference scenes. A thread stretched during a run may hold 4 times as many; beyond,
/// resampling throws (the step is rolled back and reported) instead of exhausting memory.
inline constexpr int kMaxSpheresPerThread = 1000000;

class SphereSamplingMapping final : public Mapping {
 public:
  /// basis: the spline's basis (cloned); spacing: target curvilinear distance h (m) > 0.
  /// Throws std::invalid_argument otherwise.
  SphereSamplingMapping(const CurveBasis& basis, double spacing);

  std::string typeName() const override { return "SphereSamplingMapping"; }
  int inputCount() const override { return basis_->controlPointCount(); }
  int outputCount() const override { return static_cast<int>(abscissas_.size()); }

  /// Places the centres at equal curvilinear spacing on the curve of control points q (n × 3).
  void resample(ConstPointsRef q);
  /// Room for `count` spheres, so that resampling a thread that stretches up to that count
  /// allocates nothing (the step workspace is sized once).
  void reserve(int count) {
    abscissas_.reserve(count);
    rows_.reserve(count);
    strand_of_.reserve(count);
    left_limit_.reserve(count);
    arc_of_.reserve(count);
  }

  void apply(ConstPointsRef in, PointsRef out) const override;
  void applyJ(ConstPointsRef in, ConstPointsRef v_in, PointsRef v_out) const override;
  void applyJT(ConstPointsRef in, ConstPointsRef f_out, PointsRef f_in) const override;
  SparseMatrix jacobian(ConstPointsRef in) const override;

  /// s_k of every centre (sorted, s_0 = 0, s_{K−1} = 1; a cut's abscissa twice, the end of the
  /// strand before it and the start of the next).
  const std::vector<double>& abscissas() const { return abscissas_; }
  /// Basis row of centre k.
  const geometry::BasisRow& row(int k) const { return rows_[k]; }
  /// The point (1 − t) x_k + t x_{k+1} of the chord from centre k (t ∈ [0, 1] when joinsNext(k);
  /// else centre k alone) on `body`, the body this mapping samples, as the body point whose
  /// mapping carries forces there up to the control points.
  BodyPoint chordPoint(const CurveBody& body, int k, double t) const;
  /// Whether centres k and k + 1 are joined by a chord (the same strand).
  bool joinsNext(int k) const { return k + 1 < outputCount() && strand_of_[k] == strand_of_[k + 1]; }
  /// The strand of centre k (0 for an uncut curve).
  int strandOf(int k) const { return strand_of_[k]; }
  /// An upper bound on the material length between any points of chords k and l: (|k − l| + 1)
  /// times the spacing on one strand. Lengths run along the thread as it was before any cut
  /// (the strands end to end), so that the two ends of a fresh cut, which start at one place, are
  /// as near as they were: self-collision excludes them as it excludes neighbours.
  double chordDistanceBound(int k, int l) const;
  /// The material length between the chord points k + t and l + u (t, u ∈ [0, 1]), measured as
  /// chordDistanceBound measures it.
  double arcDistance(int k, double t, int l, double u) const;
  /// Arc length L of the curve at the last resample (m, the sum over strands) and the largest
  /// actual spacing L_t / (K_t − 1) of its strands.
  double length() const { return length_; }
  double spacing() const { return actual_spacing_; }
  double targetSpacing() const { return spacing_; }

 private:
  std::unique_ptr<CurveBasis> basis_;
  double spacing_;
  double length_ = 0.0;
  double actual_spacing_ = 0.0;
  std::vector<Strand> strands_;
  std::vector<double> abscissas_;
  std::vector<geometry::BasisRow> rows_;
  std::vector<int> strand_of_;          // strand of every centre
  std::vector<char> left_limit_;        // its row is the left limit (a strand's end at a cut)
  std::vector<double> strand_spacing_;  // L_t / (K_t − 1) of every strand at the last resample
  std::vector<double> arc_of_;          // arc length from s = 0 to every centre, strands end to end
  /// K of strand t from its current length (table_length_ filled): ⌈L / h⌉ + 1, or for a polyline
  /// Σ ⌈ℓ_p / h⌉ over its pieces plus one, so that its vertices are centres; a double, compared
  /// with the limit before it is cast.
  double centresOnStrand(int t) const;
  /// Whether strand t is a polyline (degree 1, at least one piece): sampled piece by piece.
  bool isPolyline(int t) const;
  /// Centres a polyline's piece starting at table entry j holds before its end: ⌈ℓ_p / h⌉.
  double centresOnPiece(int j) const;
  /// Places a polyline strand's `count` centres piece by piece (abscissas, arc lengths from the
  /// strand's start, strand spacing: the longest chord).
  void samplePolylineStrand(int t, int first, int count);
  /// Places the centres of strand t from index `first` on, at arc lengths from `base` (table
  /// lengths computed); returns K_t.
  int sampleStrand(int t, int first, double base);

  // Arc-length table (model data, from the basis only): abscissas, basis derivatives there and
  // at the 4 Gauss nodes of every table interval (those of the interval ending at entry j at
  // 4 j..4 j + 3); lengths (from 0 at each strand's start) and speeds filled by resample.
  // Strand t has the entries strand_table_begin_[t] .. strand_table_begin_[t + 1] − 1.
  struct Derivative {
    int first = 0;
    int count = 0;
    std::array<double, geometry::BasisRow::kMaxSupport> d1{};
  };
  std::vector<double> table_s_;
  std::vector<Derivative> table_derivative_, gauss_;
  std::vector<double> table_length_, table_speed_;
  std::vector<int> strand_table_begin_;
};

}  // namespace filum::collision
