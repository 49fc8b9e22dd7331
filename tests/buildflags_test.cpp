// What cmake/TargetArch.cmake promises of every target: arithmetic, and so images, that do not
// depend on the instruction set the renderer was built for.
#include <gtest/gtest.h>

namespace {

// Out of line, and fed from volatiles, so that the compiler folds nothing at compile time.
[[gnu::noinline]] float MultiplyAdd(float a, float b, float c) { return a * b + c; }

}  // namespace

// -ffp-contract=off: a * b + c rounds twice, as on a CPU without FMA, even in a build for one
// with it. Here the product 1 + 2^-11 + 2^-24 rounds (a tie, to even) to 1 + 2^-11 and the sum
// is 0; a fused multiply-add would keep the 2^-24 (as GCC's default contraction does for
// x86-64-v3).
TEST(BuildFlags, MultiplyAddRoundsTwiceWhateverTheTarget) {
    volatile float a = 1 + 0x1p-12f, c = -(1 + 0x1p-11f);
    EXPECT_EQ(MultiplyAdd(a, a, c), 0.f);
}
