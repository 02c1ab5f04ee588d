// Broad phase: every pair of bounding spheres that overlap, |c_i − c_j| <= r_i + r_j, in time
// linear in the number of spheres — the "voxel grid" broad phase of [Lenoir talk 2008] (intestines), as a
// spatial hash (Teschner, Heidelberger, Müller, Pomeranets & Gross, "Optimized spatial hashing for
// collision detection of deformable objects", VMV 2003).
//
// Space is cut into cubic cells of side h (by default twice the largest radius). Every sphere is
// entered once, in the cell of its centre; cells are hashed into a table of T >= 2n buckets,
//   hash(i, j, k) = mix(73856093 i ⊕ 19349663 j ⊕ 83492791 k) mod T
// (mix: MurmurHash3's finalizer, which brings the high bits down to the ones T keeps),
// and the entries sorted by bucket with one counting sort (O(n + T)). Two spheres overlap only
// if their centres are within 2 r_max, so their cells differ by at most R = ⌈2 r_max / h⌉ per
// axis (R = 1 by default). Each occupied cell is paired with itself and with the half of its
// neighbourhood [−R, R]³ that comes after it in lexicographic order (13 cells for R = 1), so
// each pair of cells — and each pair of spheres — is visited once, with one table lookup per
// neighbour cell rather than per sphere. Cells that share a bucket are told apart by their
// indices. The pairs are returned sorted (i < j, lexicographic) by a counting sort on i and an
// insertion sort of each sphere's few partners, so that results never depend on the hash.
// Cost O(n + p) for n spheres and p pairs of neighbouring centres, which is O(n) when the cell
// is about the spheres' size and they do not pile up (a bounded number of centres per cell).
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include "filum/core/types.hpp"

namespace filum::collision {

struct BoundingSphere {
  Vec3 center = Vec3::Zero();  // m
  double radius = 0.0;         // m, >= 0
};

using IndexPair = std::pair<int, int>;

class UniformGridBroadPhase {
 public:
  /// cell_size (m) > 0, or 0: twice the largest radius of each query (at least 1e-12).
  explicit UniformGridBroadPhase(double cell_size = 0.0) : cell_size_(cell_size) {}

  /// Pairs a query may find per sphere, at most, unless told otherwise: with the cell twice the
  /// largest radius, a sphere of a thread overlaps a few dozen others of similar size at most;
  /// this many on average is more than any thread scene shows, and room for them is reserved
  /// from the first query on (the step workspace is sized once).
  static constexpr std::size_t kPairsPerSphere = 16;

  /// Every pair (i, j), i < j, with |c_i − c_j| <= r_i + r_j, sorted; `pairs` is cleared first.
  /// Stops at `max_pairs` pairs (default 2 kPairsPerSphere per sphere, the room reserved) and
  /// returns false: the spheres overlap far more than threads do (a body swept far in one step),
  /// and the caller decides (a smaller step); the work stays linear in the spheres and nothing
  /// is allocated.
  /// No allocation once the buffers have reached the size of the scene.
  bool findPairs(const std::vector<BoundingSphere>& spheres, std::vector<IndexPair>& pairs, std::size_t max_pairs = 0);

  double cellSize() const { return cell_size_; }
  /// Cell side used by the last query (m).
  double lastCellSize() const { return last_cell_size_; }

 private:
  struct Entry {
    int item;
    int cell[3];
    double center[3];  // the sphere, copied so that scans of a cell read contiguous memory
    double radius;
  };

  double cell_size_;
  double last_cell_size_ = 0.0;
  std::vector<Entry> sorted_;            // entries sorted by bucket
  std::vector<std::uint32_t> bucket_;    // bucket of every sphere
  std::vector<int> bucket_start_;        // entries of bucket b: [bucket_start_[b], bucket_start_[b+1])
  std::vector<int> cell_;                // cell of every sphere, 3 per sphere
  std::vector<int> members_;             // entries of the cell being processed
  std::vector<IndexPair> found_;         // pairs in cell order
  std::vector<int> first_start_;         // counting sort of the pairs by first index

  /// The overlapping pairs of the sorted entries into found_, cell by cell, at most max_pairs;
  /// false when it stopped there.
  bool collectPairs(int n, int R, std::uint32_t mask, std::size_t max_pairs);
  /// found_ sorted by (first, second) into `pairs`.
  void sortPairs(int n, std::vector<IndexPair>& pairs);
};

/// The same pairs by testing all n (n − 1)/2 pairs (the reference of the tests).
std::vector<IndexPair> bruteForcePairs(const std::vector<BoundingSphere>& spheres);

}  // namespace filum::collision
