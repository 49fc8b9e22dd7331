// The renderer's refusal of a CPU that lacks the instructions it was compiled for
// (cmake/TargetArch.cmake): a message and exit status 2 instead of an illegal instruction in
// the middle of a study. It runs before every C++ static initializer (constructor priority
// 101), and is itself compiled for the x86-64 baseline, so it can run on any x86-64 CPU.
#if defined(__x86_64__) && (defined(__AVX2__) || defined(__AVX512F__))

#include <cstdio>
#include <cstdlib>

namespace {

__attribute__((constructor(101), target("arch=x86-64"))) void RefuseACPUWithoutTheBuildsInstructions() {
    __builtin_cpu_init();
    bool supported = true;
#if defined(__AVX2__)
    supported = supported && __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                __builtin_cpu_supports("bmi2");
#endif
#if defined(__AVX512F__)
    supported = supported && __builtin_cpu_supports("avx512f");
#endif
    if (supported)
        return;
    std::fputs("pbrt_ext: this CPU lacks instructions this build was compiled for (AVX2, FMA "
               "and BMI2, or AVX-512); configure a build for it with "
               "-DPBRT_EXT_TARGET_ARCH=none (cmake/TargetArch.cmake)\n",
               stderr);
    std::_Exit(2);
}

}  // namespace

#endif
