#include "filum/collision/knot_type.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <vector>

#include "filum/collision/knot_determinant.hpp"
#include "knot_diagram.hpp"

namespace filum::collision {

namespace {

LaurentPolynomial multiply(const LaurentPolynomial& a, const LaurentPolynomial& b) {
  LaurentPolynomial c;
  for (const auto& [i, x] : a)
    for (const auto& [j, y] : b) c[i + j] += x * y;
  for (auto it = c.begin(); it != c.end();) it = it->second == 0 ? c.erase(it) : std::next(it);
  return c;
}

LaurentPolynomial mirror(const LaurentPolynomial& p) {
  LaurentPolynomial m;
  for (const auto& [e, c] : p) m[-e] = c;
  return m;
}

/// Removes kinks: a crossing whose over and under passages are consecutive along the curve
/// (Reidemeister I; the writhe correction of V absorbs it). Repeated until none is left.
void removeKinks(std::vector<DiagramCrossing>& list) {
  for (bool removed = true; removed;) {
    removed = false;
    const int n = static_cast<int>(list.size());
    std::vector<std::pair<double, int>> passages;  // (position, crossing)
    for (int c = 0; c < n; ++c) {
      passages.push_back({list[c].over, c});
      passages.push_back({list[c].under, c});
    }
    std::sort(passages.begin(), passages.end());
    for (int k = 0; k < 2 * n && !removed; ++k) {
      if (passages[k].second != passages[(k + 1) % (2 * n)].second) continue;
      list.erase(list.begin() + passages[k].second);
      removed = true;
    }
  }
}

/// ⟨K⟩ as a Laurent polynomial in A, by the state sum (see the header).
LaurentPolynomial bracket(const std::vector<DiagramCrossing>& list) {
  const int n = static_cast<int>(list.size());
  if (n == 0) return {{0, 1}};
  // Passages in order along the curve: edge k runs from passage k to passage k + 1.
  std::vector<std::pair<double, int>> passages;  // (position, 2c for over, 2c + 1 for under)
  for (int c = 0; c < n; ++c) {
    passages.push_back({list[c].over, 2 * c});
    passages.push_back({list[c].under, 2 * c + 1});
  }
  std::sort(passages.begin(), passages.end());
  const int edges = 2 * n;
  std::vector<int> at(2 * n);  // passage index of (crossing, strand)
  for (int k = 0; k < edges; ++k) at[passages[k].second] = k;
  // The four edge ends at each crossing: over in/out, under in/out (edge indices), and which
  // pairs the A- and B-smoothings join.
  struct Joins {
    int a1, a2, a3, a4;  // A: (a1, a2), (a3, a4)
    int b1, b2, b3, b4;  // B
  };
  std::vector<Joins> joins(n);
  for (int c = 0; c < n; ++c) {
    const int over_in = (at[2 * c] + edges - 1) % edges, over_out = at[2 * c];
    const int under_in = (at[2 * c + 1] + edges - 1) % edges, under_out = at[2 * c + 1];
    if (list[c].sign > 0)  // o × u > 0: A joins each over end to the under end clockwise of it
      joins[c] = {over_out, under_in, over_in, under_out, over_out, under_out, over_in, under_in};
    else
      joins[c] = {over_out, under_out, over_in, under_in, over_out, under_in, over_in, under_out};
  }
  // δ^k, k = 0 .. 2n, δ = −A² − A⁻².
  std::vector<LaurentPolynomial> delta(edges + 1);
  delta[0] = {{0, 1}};
  for (int k = 1; k <= edges; ++k) delta[k] = multiply(delta[k - 1], {{2, -1}, {-2, -1}});
  // Σ_states A^(#A − #B) δ^(loops − 1): counted as (a − b, loops) pairs first.
  std::map<std::pair<int, int>, long> counts;
  std::vector<int> parent(edges);
  auto find = [&](int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (unsigned long state = 0; state < (1ul << n); ++state) {
    std::iota(parent.begin(), parent.end(), 0);
    int loops = edges;
    auto unite = [&](int x, int y) {
      x = find(x);
      y = find(y);
      if (x != y) {
        parent[x] = y;
        --loops;
      }
    };
    int a_minus_b = 0;
    for (int c = 0; c < n; ++c) {
      const Joins& j = joins[c];
      if (state >> c & 1ul) {
        unite(j.b1, j.b2);
        unite(j.b3, j.b4);
        --a_minus_b;
      } else {
        unite(j.a1, j.a2);
        unite(j.a3, j.a4);
        ++a_minus_b;
      }
    }
    ++counts[{a_minus_b, loops}];
  }
  LaurentPolynomial sum;
  for (const auto& [key, count] : counts)
    for (const auto& [e, c] : delta[key.second - 1]) sum[e + key.first] += count * c;
  for (auto it = sum.begin(); it != sum.end();) it = it->second == 0 ? sum.erase(it) : std::next(it);
  return sum;
}

/// a / b when b divides a exactly in Z[t, t⁻¹], by long division from the highest exponent;
/// false otherwise. While the span of the remainder is at least b's, the remainder's highest
/// exponent falls and its lowest does not, so the loop ends.
bool divideExactly(LaurentPolynomial a, const LaurentPolynomial& b, LaurentPolynomial& quotient) {
  quotient.clear();
  const int b_low = b.begin()->first, b_high = b.rbegin()->first;
  const long b_lead = b.rbegin()->second;
  while (!a.empty()) {
    const auto [a_high, a_lead] = *a.rbegin();
    if (a_high - a.begin()->first < b_high - b_low || a_lead % b_lead != 0) return false;
    const int shift = a_high - b_high;
    const long factor = a_lead / b_lead;
    quotient[shift] = factor;
    for (const auto& [e, c] : b) a[e + shift] -= factor * c;
    for (auto it = a.begin(); it != a.end();) it = it->second == 0 ? a.erase(it) : std::next(it);
  }
  return true;
}

/// V of a throw of k wraps closed far away: the (2, 2k + 1) torus knot (k = 1 the half knot, the
/// trefoil; k = 2 the surgeon's double throw, the cinquefoil). For the torus knot T(p, q)
/// (Jones, "Hecke algebra representations of braid groups and link polynomials", Ann. Math. 126
/// (1987) 335, Thm. 14.1), V(t) = t^((p−1)(q−1)/2) (1 − t^(p+1) − t^(q+1) + t^(p+q)) / (1 − t²);
/// here V = t^k (1 − t³ − t^(2k+2) + t^(2k+3)) / (1 − t²): k = 1 gives t + t³ − t⁴.
LaurentPolynomial throwPolynomial(int wraps) {
  const LaurentPolynomial numerator{{wraps, 1}, {wraps + 3, -1}, {3 * wraps + 2, -1}, {3 * wraps + 3, 1}};
  LaurentPolynomial v;
  divideExactly(numerator, {{0, 1}, {2, -1}}, v);  // exact: 1 − t² divides the numerator
  return v;
}

constexpr int kMaxWraps = 3;  // nameOfThrows names single throws up to septafoil

/// The throws (signed wraps, in the order of `candidates`) whose product of V is `jones`: every
/// multiset of throw polynomials with at most `crossings` crossings in all (2k + 1 per throw:
/// the span of V of a product of throws is Σ (2k + 1), and the span of V is at most the
/// crossings of any diagram), counted in `found` (the search stops at 2: the decomposition is
/// then not unique).
void searchThrows(const LaurentPolynomial& jones, int crossings, std::size_t first, std::vector<int>& current,
                  std::vector<int>& throws, int& found) {
  if (jones == LaurentPolynomial{{0, 1}}) {
    if (++found == 1) throws = current;
    return;
  }
  static const std::vector<std::pair<int, LaurentPolynomial>> candidates = [] {
    std::vector<std::pair<int, LaurentPolynomial>> list;  // by wraps down, + before −
    for (int k = kMaxWraps; k >= 1; --k) {
      list.emplace_back(k, throwPolynomial(k));
      list.emplace_back(-k, mirror(throwPolynomial(k)));
    }
    return list;
  }();
  LaurentPolynomial rest;
  for (std::size_t i = first; i < candidates.size() && found < 2; ++i) {
    const int cost = 2 * std::abs(candidates[i].first) + 1;
    if (cost > crossings || !divideExactly(jones, candidates[i].second, rest)) continue;
    current.push_back(candidates[i].first);
    searchThrows(rest, crossings - cost, i, current, throws, found);
    current.pop_back();
  }
}

/// Whether the throws (sorted by wraps down, + before −) are the mirror of the first of the
/// pair {throws, their mirror} in that order: the sorted sequences compared lexicographically
/// by candidate rank (wraps down, + before −). An amphichiral multiset is its own mirror: false.
bool isMirrorOfCanonical(const std::vector<int>& throws) {
  const auto rank = [](int w) { return 2 * (kMaxWraps - std::abs(w)) + (w < 0 ? 1 : 0); };
  std::vector<int> mirrored;
  for (int w : throws) mirrored.push_back(-w);
  std::sort(mirrored.begin(), mirrored.end(), [&](int a, int b) { return rank(a) < rank(b); });
  return std::lexicographical_compare(mirrored.begin(), mirrored.end(), throws.begin(), throws.end(),
                                      [&](int a, int b) { return rank(a) < rank(b); });
}

/// The knot's name from its throws (sorted by wraps down, + before −).
std::string nameOfThrows(const std::vector<int>& throws) {
  const auto wraps = [&](std::size_t i) { return std::abs(throws[i]); };
  if (throws.empty()) return "unknot";
  if (throws.size() == 1) {
    static_assert(kMaxWraps == 3, "a name for each single throw up to kMaxWraps");
    const char* single[kMaxWraps + 1] = {"", "trefoil", "cinquefoil", "septafoil"};
    return single[wraps(0)];
  }
  const bool same_sense = throws.size() == 2 && (throws[0] > 0) == (throws[1] > 0);
  if (throws.size() == 2 && wraps(0) == 1) return same_sense ? "granny" : "square";
  if (throws.size() == 2 && wraps(0) == 2 && wraps(1) == 1) return same_sense ? "surgeon's granny" : "surgeon's";
  return std::to_string(throws.size()) + " throws";
}

/// Thirteen directions spread over the half sphere (a Fibonacci lattice, skewed off the axes).
std::vector<Vec3> directions() {
  std::vector<Vec3> out;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int k = 0; k < 13; ++k) {
    const double z = 1.0 - (k + 0.5) / 13.0;
    const double r = std::sqrt(1.0 - z * z), phi = golden * k + 0.1234;
    out.emplace_back(r * std::cos(phi), r * std::sin(phi), z);
  }
  return out;
}

}  // namespace

std::string toString(const LaurentPolynomial& p) {
  if (p.empty()) return "0";
  std::ostringstream out;
  bool first = true;
  for (const auto& [e, c] : p) {
    const long magnitude = std::abs(c);
    out << (first ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + "));
    first = false;
    if (magnitude != 1 || e == 0) out << magnitude;
    if (e != 0) out << (magnitude != 1 ? "*" : "") << "t";
    if (e != 0 && e != 1) out << '^' << e;
  }
  return out.str();
}

namespace {

/// V(t) of a diagram (kinks removed); false if its exponents are not integers (not one closed curve).
bool jonesOfDiagram(const std::vector<DiagramCrossing>& list, LaurentPolynomial& jones) {
  int writhe = 0;
  for (const DiagramCrossing& c : list) writhe += c.sign;
  // V = (−A³)^(−w) ⟨K⟩; exponents of A are then multiples of 4 and t = A⁻⁴.
  const LaurentPolynomial b = bracket(list);
  jones.clear();
  for (const auto& [e, c] : b) {
    const int exponent = e - 3 * writhe;
    if (exponent % 4 != 0) return false;  // not a knot diagram (cannot happen for one closed curve)
    jones[-exponent / 4] += (writhe % 2 == 0 ? 1 : -1) * c;
  }
  return true;
}

}  // namespace

bool jonesPolynomial(const Points& closed, const Vec3& direction, LaurentPolynomial& jones, int* crossings,
                     int max_crossings) {
  std::vector<DiagramCrossing> list;
  if (!projectDiagram(closed, direction, list)) return false;
  removeKinks(list);
  if (crossings) *crossings = static_cast<int>(list.size());
  if (static_cast<int>(list.size()) > std::min(max_crossings, kMaxKnotCrossings)) return false;
  return jonesOfDiagram(list, jones);
}

KnotType knotType(const Points& closed, int max_crossings) {
  KnotType best;
  // The diagram with the fewest crossings (after kinks) over the directions; the state sum, 2ⁿ,
  // for that one only.
  std::vector<DiagramCrossing> fewest, list;
  bool found = false;
  for (const Vec3& d : directions()) {
    if (!projectDiagram(closed, d, list)) continue;
    removeKinks(list);
    if (static_cast<int>(list.size()) > std::min(max_crossings, kMaxKnotCrossings)) continue;
    if (!found || list.size() < fewest.size()) {
      fewest = list;
      found = true;
    }
  }
  if (!found || !jonesOfDiagram(fewest, best.jones)) return best;
  best.crossings = static_cast<int>(fewest.size());
  for (const DiagramCrossing& c : fewest) best.crossing_passages.emplace_back(c.over, c.under);
  // The figure-eight (amphichiral), then a product of throws: the Jones polynomial of a
  // connected sum is the product of its summands' (Jones 1987, §7).
  const LaurentPolynomial figure_eight{{-2, 1}, {-1, -1}, {0, 1}, {1, -1}, {2, 1}};
  if (best.jones == figure_eight) {
    best.name = "figure-eight";
    return best;
  }
  std::vector<int> current, throws;
  int decompositions = 0;
  searchThrows(best.jones, best.crossings, 0, current, throws, decompositions);
  best.name = "other";
  if (decompositions != 1) return best;
  best.throws = throws;
  best.name = nameOfThrows(throws);
  best.mirrored = isMirrorOfCanonical(throws);
  return best;
}

std::string throwsString(const std::vector<int>& throws) {
  std::ostringstream out;
  for (std::size_t i = 0; i < throws.size(); ++i) out << (i ? " " : "") << (throws[i] > 0 ? "+" : "") << throws[i];
  return out.str();
}

KnotSpan knotSpan(const KnotType& type, int open_points) {
  KnotSpan span;
  if (type.name == "unknot" || type.name == "unknown") return span;
  const double end = open_points - 1;  // the thread's last vertex: the closing arc starts there
  for (const auto& [over, under] : type.crossing_passages) {
    if (over >= end || under >= end) continue;  // the thread under or over the closing arc
    const double lo = std::min(over, under), hi = std::max(over, under);
    span.first = span.found ? std::min(span.first, lo) : lo;
    span.last = span.found ? std::max(span.last, hi) : hi;
    span.found = true;
  }
  return span;
}

}  // namespace filum::collision
