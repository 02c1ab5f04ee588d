// Buffers of a steady step grow geometrically and never shrink (docs/architecture.md, "Model and
// state"): a count that changes from step to step (contacts, rows) allocates when it reaches a new
// maximum, by doubling, and never otherwise. std::vector's resize and copy assignment allocate
// exactly the size asked, so a size growing by one each step would allocate every step.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace filum {

/// v.resize(n), its capacity grown to twice n when it is short.
template <class T>
void resizeGrowing(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) v.reserve(2 * n);
  v.resize(n);
}

/// to = from, to's capacity grown geometrically.
template <class T>
void assignGrowing(std::vector<T>& to, const std::vector<T>& from) {
  if (to.capacity() < from.size()) to.reserve(std::max(from.size(), 2 * to.capacity()));
  to.assign(from.begin(), from.end());
}

}  // namespace filum
