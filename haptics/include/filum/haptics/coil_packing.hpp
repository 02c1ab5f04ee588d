// CoilPacking: how full an aneurysm is of coil — the packing density an interventional
// neuroradiologist reports after coiling (the sac's recanalization risk falls as it rises; about
// 20–25 % by volume is the usual aim, Sluzewski et al., Radiology 2004):
//   PD = Σ_c π r_c² L_c / V,
// r_c the radius of coil c, L_c the length of its centre line inside the aneurysm, V the
// aneurysm's volume. The aneurysm is a set of branches of the vessel tree (the sac, its neck):
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
// curve loses its sagitta's share, l³κ²/24.
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
  /// L: the length of the body's centre line inside the aneurysm at the scene's positions q (m),
  /// from `pieces` chords.
  double lengthInside(const CurveBody& body, const VecX& q, int pieces = 512) const;
  /// PD for coils of radius r with a total length L inside.
  double density(double radius, double length) const;

 private:
  geometry::VesselTree tree_;  // a copy: independent of the tree it was made from
  std::vector<int> branches_;
  double spacing_ = 0.0;
  double volume_ = 0.0;
};

}  // namespace filum::haptics
