// CoilPacking: how full an aneurysm is of coil — the packing density an interventional
// neuroradiologist reports after coiling (the sac's recanalization risk falls as it rises; about
// 20–25 % by volume is the usual aim, Sluzewski et al., Radiology 2004):
//   PD = Σ_c ∫_{inside} π r_c(s)² dℓ / V,
// r_c(s) the radius of coil c at abscissa s (one radius for most coils, by spans for a coil with
// a stretch-resistant or thinner section: CurveBody::radiusAt), the integral over its centre line
// inside the aneurysm (π r_c² L_c for one radius, L_c the length inside), V the aneurysm's
// volume. The aneurysm is a set of branches of the vessel tree (the sac, its neck):
// the lumen's points, φ > 0, whose largest branch field is one of them (geometry/vessel_tree.hpp,
// Sample::branch), so it ends where the parent artery's field takes over, along the parent's wall.
//
// V: the midpoint rule on a cubic grid of spacing h over the branches' box — a cell counts when
// its centre is in the aneurysm. Its error is the lattice-point discrepancy of the region: for a
// ball, relative O((h/R)^{3/2}) (Gauss's sphere problem); where the boundary has flat directions
// (a cylinder along a grid axis: the slices' errors add up) O((h/R)^{4/3}); where it has a flat
// face or an edge (the cut across the neck where the parent artery's field takes over) first
// order, up to half a layer of cells over that face. These are orders with constants of order
// one, not bounds: measured 3.3e-3 for a capsule at h = R/25 (tests/haptics/coil_packing_test.cpp).
// The default h is the aneurysm's smallest branch radius over 25.
// L_c: the centre line sampled at N + 1 abscissas (N = 512 by default); a piece between two
// samples counts (with its chord length) when its midpoint is in the aneurysm. Errors: below one
// piece per crossing of the boundary; a chord over a node of a polyline (a rod) cuts the node's
// corner and loses at most l θ²/8 (θ the turn at the node, l the piece); a chord of a smooth
// curve loses its sagitta's share, l³κ²/24. The volume takes each piece's radius at its middle
// abscissa: exact on a piece within one span; a piece across a step of the section errs by at
// most π |r₁² − r₂²| l / 2.
#pragma once

#include <string>
#include <vector>

#include "filum/core/curve_body.hpp"
#include "filum/geometry/vessel_tree.hpp"

namespace filum::haptics {

class CoilPacking {
 public:
  /// Cells the volume integral may use: checked before any work (a spacing far too small for
  /// the box is refused, not run for hours).
  static constexpr long kMaxCells = 50'000'000;

  /// The aneurysm made of `branches` (indices into `tree`, at least one) with grid spacing h (m;
  /// <= 0: the branches' smallest radius / 25). Throws std::invalid_argument for no branches, an
  /// index out of range, a spacing above a quarter of the smallest radius, a grid above
  /// kMaxCells, or no cell in the aneurysm (so V > 0).
  CoilPacking(const geometry::VesselTree& tree, std::vector<int> branches, double spacing = 0.0);

  /// Whether x lies in the aneurysm: inside the lumen, in one of its branches.
  bool contains(const Vec3& x) const;
  /// V (m³).
  double volume() const { return volume_; }
  double spacing() const { return spacing_; }
  const std::vector<int>& branches() const { return branches_; }
  /// What of a body lies in the aneurysm: its centre line's length L (m) and its volume
  /// ∫ π r(s)² dℓ (m³) there.
  struct Inside {
    double length = 0.0;
    double volume = 0.0;
  };
  /// The body's share of the aneurysm at the scene's positions q, from `pieces` chords.
  Inside inside(const CurveBody& body, const VecX& q, int pieces = 512) const;
  /// L alone (inside(...).length).
  double lengthInside(const CurveBody& body, const VecX& q, int pieces = 512) const {
    return inside(body, q, pieces).length;
  }
  /// PD for coils whose volume inside is `coil_volume` (m³): coil_volume / V.
  double density(double coil_volume) const { return coil_volume / volume_; }

 private:
  geometry::VesselTree tree_;  // a copy: independent of the tree it was made from
  std::vector<int> branches_;
  double spacing_ = 0.0;
  double volume_ = 0.0;
};

}  // namespace filum::haptics
