// FlushDenormals: while an instance lives, the calling thread treats subnormal doubles
// (|x| < 2.2e-308) as zero — SSE's MXCSR flags FTZ (results) and DAZ (inputs) — and the
// previous mode comes back when it is destroyed. Scene::step holds one.
//
// Why: M⁻¹ w, the response of a thread to a constraint or contact anchor, decays like 0.535^k
// with the distance k in control points (lagrange_multiplier_solver.hpp), so about 1100 control
// points away it enters the subnormal range, where x86 arithmetic is 10–100 times slower. On
// long threads that made band solves up to 16 times slower than the same solve on normal
// numbers (apps/bench/bench_constraints, n = 2500 and 5000). Flushing is deterministic (the same
// bits on every run) and changes only values below 2.2e-308, which no physical quantity of a
// scene in SI units reaches. Elsewhere than x86-64 this is a no-op.
#pragma once

#if defined(__x86_64__) || defined(_M_X64)
#include <xmmintrin.h>
#define FILUM_HAS_MXCSR 1
#else
#define FILUM_HAS_MXCSR 0
#endif

namespace filum {

class FlushDenormals {
 public:
  FlushDenormals() {
#if FILUM_HAS_MXCSR
    saved_ = _mm_getcsr();
    _mm_setcsr(saved_ | kFlushToZero | kDenormalsAreZero);
#endif
  }
  ~FlushDenormals() {
#if FILUM_HAS_MXCSR
    _mm_setcsr(saved_);
#endif
  }
  FlushDenormals(const FlushDenormals&) = delete;
  FlushDenormals& operator=(const FlushDenormals&) = delete;

 private:
  static constexpr unsigned kFlushToZero = 1u << 15;
  static constexpr unsigned kDenormalsAreZero = 1u << 6;
  unsigned saved_ = 0;
};

}  // namespace filum
