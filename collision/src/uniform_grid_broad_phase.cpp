#include "filum/collision/uniform_grid_broad_phase.hpp"

#include <algorithm>
#include <cmath>

namespace filum::collision {

namespace {

bool overlap(const BoundingSphere& a, const BoundingSphere& b) {
  const double r = a.radius + b.radius;
  return (a.center - b.center).squaredNorm() <= r * r;
}

std::uint32_t hashCell(int i, int j, int k, std::uint32_t mask) {
  std::uint32_t h = static_cast<std::uint32_t>(i) * 73856093u ^ static_cast<std::uint32_t>(j) * 19349663u ^
                    static_cast<std::uint32_t>(k) * 83492791u;
  // Mix the high bits into the low ones that the mask keeps (the products' low bits depend only
  // on the low bits of the indices): the finalizer of MurmurHash3.
  h ^= h >> 16;
  h *= 0x85ebca6bu;
  h ^= h >> 13;
  return h & mask;
}

int cellIndex(double x, double inverse_h) { return static_cast<int>(std::floor(x * inverse_h)); }

}  // namespace

bool UniformGridBroadPhase::findPairs(const std::vector<BoundingSphere>& spheres, std::vector<IndexPair>& pairs,
                                      std::size_t max_pairs) {
  pairs.clear();
  const int n = static_cast<int>(spheres.size());
  if (n < 2) return true;
  // Room for the pairs of a dense tangle from the first call on, so that a knot tightening over
  // many steps does not grow the lists step after step (the step workspace is sized once).
  const std::size_t room = kPairsPerSphere * static_cast<std::size_t>(n);
  if (max_pairs == 0) max_pairs = 2 * room;
  if (found_.capacity() < room) found_.reserve(2 * room);  // twice: the sphere count may grow
  if (pairs.capacity() < room) pairs.reserve(2 * room);
  // The per-sphere tables get room for twice as many spheres: a stretching thread adds spheres.
  if (members_.capacity() < static_cast<std::size_t>(n)) {
    const std::size_t spheres_room = 2 * static_cast<std::size_t>(n) + 2;
    members_.reserve(spheres_room);
    cell_.reserve(3 * spheres_room);
    bucket_.reserve(spheres_room);
    sorted_.reserve(spheres_room);
    first_start_.reserve(spheres_room + 1);
    bucket_start_.reserve(4 * spheres_room + 1);  // the hash table has <= 4n buckets
  }

  // Cell side h: given, or twice the largest radius (partners then lie in the 27 cells around).
  double largest = 0.0;
  for (const BoundingSphere& s : spheres) largest = std::max(largest, s.radius);
  double h = cell_size_;
  if (!(h > 0.0)) h = std::max(2.0 * largest, 1e-12);
  last_cell_size_ = h;
  const double inverse_h = 1.0 / h;

  // One entry per sphere, in the cell of its centre; counting sort by bucket (stable).
  std::uint32_t table = 1;
  while (table < 2u * static_cast<std::uint32_t>(n)) table <<= 1;
  const std::uint32_t mask = table - 1;
  cell_.resize(3 * n);
  bucket_.resize(n);
  bucket_start_.assign(table + 1, 0);
  for (int i = 0; i < n; ++i) {
    for (int a = 0; a < 3; ++a) cell_[3 * i + a] = cellIndex(spheres[i].center[a], inverse_h);
    bucket_[i] = hashCell(cell_[3 * i], cell_[3 * i + 1], cell_[3 * i + 2], mask);
    ++bucket_start_[bucket_[i] + 1];
  }
  for (std::uint32_t b = 0; b < table; ++b) bucket_start_[b + 1] += bucket_start_[b];
  sorted_.resize(n);
  for (int i = 0; i < n; ++i) {
    Entry& e = sorted_[bucket_start_[bucket_[i]]++];
    e.item = i;
    for (int a = 0; a < 3; ++a) {
      e.cell[a] = cell_[3 * i + a];
      e.center[a] = spheres[i].center[a];
    }
    e.radius = spheres[i].radius;
  }
  // bucket_start_[b] now holds the end of bucket b; shift back to starts.
  for (std::uint32_t b = table; b > 0; --b) bucket_start_[b] = bucket_start_[b - 1];
  bucket_start_[0] = 0;

  // Half of the neighbourhood [−R, R]³ after (0, 0, 0) in lexicographic order.
  const int R = std::max(1, static_cast<int>(std::ceil(2.0 * largest * inverse_h - 1e-12)));
  found_.clear();
  const bool complete = collectPairs(n, R, mask, max_pairs);
  sortPairs(n, pairs);
  return complete;
}

bool UniformGridBroadPhase::collectPairs(int n, int R, std::uint32_t mask, std::size_t max_pairs) {
  // |c_i − c_j|² <= (r_i + r_j)² for two entries; false when the budget is spent.
  auto test = [&](const Entry& u, const Entry& w) {
    const double dx = u.center[0] - w.center[0], dy = u.center[1] - w.center[1], dz = u.center[2] - w.center[2];
    const double r = u.radius + w.radius;
    if (dx * dx + dy * dy + dz * dz <= r * r) found_.emplace_back(std::min(u.item, w.item), std::max(u.item, w.item));
    return found_.size() < max_pairs;
  };
  // Cells in the order of their smallest sphere index (threads are sampled along their length, so
  // this walks space coherently and keeps memory accesses local).
  for (int i = 0; i < n; ++i) {
    const int* c = &cell_[3 * i];
    const std::uint32_t b = bucket_[i];
    members_.clear();
    bool processed = false;
    for (int f = bucket_start_[b]; f < bucket_start_[b + 1] && !processed; ++f) {
      const Entry& entry = sorted_[f];
      if (entry.cell[0] != c[0] || entry.cell[1] != c[1] || entry.cell[2] != c[2]) continue;
      processed = entry.item < i;  // the cell was processed from a smaller index
      members_.push_back(f);
    }
    if (processed) continue;
    // Pairs within the cell.
    for (std::size_t u = 0; u < members_.size(); ++u)
      for (std::size_t w = u + 1; w < members_.size(); ++w)
        if (!test(sorted_[members_[u]], sorted_[members_[w]])) return false;
    // Pairs with the cells after it.
    for (int dx = 0; dx <= R; ++dx)
      for (int dy = (dx == 0 ? 0 : -R); dy <= R; ++dy)
        for (int dz = (dx == 0 && dy == 0 ? 1 : -R); dz <= R; ++dz) {
          const int x = c[0] + dx, y = c[1] + dy, z = c[2] + dz;
          const std::uint32_t nb = hashCell(x, y, z, mask);
          for (int f = bucket_start_[nb]; f < bucket_start_[nb + 1]; ++f) {
            const Entry& other = sorted_[f];
            if (other.cell[0] != x || other.cell[1] != y || other.cell[2] != z) continue;
            for (int m : members_)
              if (!test(sorted_[m], other)) return false;
          }
        }
  }
  return true;
}

void UniformGridBroadPhase::sortPairs(int n, std::vector<IndexPair>& pairs) {
  // Sorted output without a comparison sort: counting sort by first index (stable), then each
  // run of equal first indices (a sphere's few partners) by insertion on the second.
  first_start_.assign(n + 1, 0);
  for (const IndexPair& p : found_) ++first_start_[p.first + 1];
  for (int i = 0; i < n; ++i) first_start_[i + 1] += first_start_[i];
  pairs.resize(found_.size());
  for (const IndexPair& p : found_) pairs[first_start_[p.first]++] = p;
  int run = 0;
  for (int i = 0; i < n; ++i) {
    const int end = first_start_[i];  // after the scatter: the end of run i
    for (int a = run + 1; a < end; ++a)
      for (int b = a; b > run && pairs[b].second < pairs[b - 1].second; --b) std::swap(pairs[b], pairs[b - 1]);
    run = end;
  }
}

std::vector<IndexPair> bruteForcePairs(const std::vector<BoundingSphere>& spheres) {
  std::vector<IndexPair> pairs;
  const int n = static_cast<int>(spheres.size());
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (overlap(spheres[i], spheres[j])) pairs.emplace_back(i, j);
  return pairs;
}

}  // namespace filum::collision
