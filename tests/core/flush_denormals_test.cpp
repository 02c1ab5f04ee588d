// FlushDenormals (modules/include/filum/core/flush_denormals.hpp): subnormal results and inputs
// are zero while it lives, and the previous mode is back after.
#include <gtest/gtest.h>

#include <cmath>

#include "filum/core/flush_denormals.hpp"

namespace filum {
namespace {

double product(double a, double b) {
  volatile double x = a, y = b;  // multiplied at run time under the current MXCSR, not folded
  return x * y;
}

TEST(FlushDenormals, SubnormalsAreZeroInsideAndBackAfter) {
#if FILUM_HAS_MXCSR
  const double tiny = 1e-300, scale = 1e-10;  // 1e-310 is subnormal (below 2.2e-308)
  ASSERT_EQ(std::fpclassify(product(tiny, scale)), FP_SUBNORMAL);
  {
    const FlushDenormals flush;
    EXPECT_EQ(product(tiny, scale), 0.0);                         // FTZ: a subnormal result is 0
    const volatile double subnormal = 1e-310;
    EXPECT_EQ(product(subnormal, 1e300), 0.0);                    // DAZ: a subnormal input is 0
    EXPECT_EQ(product(1e-150, 1e-150), 1e-150 * 1e-150);          // normal numbers untouched
  }
  EXPECT_EQ(std::fpclassify(product(tiny, scale)), FP_SUBNORMAL);  // restored
#else
  GTEST_SKIP() << "no MXCSR on this processor: FlushDenormals is a no-op";
#endif
}

}  // namespace
}  // namespace filum
