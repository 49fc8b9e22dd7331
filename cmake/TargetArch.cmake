# The instruction set every target is compiled for.
#
# pbrt-v4 compiles for the building machine (-march=native, its PBRT_BUILD_NATIVE_EXECUTABLE).
# Here "auto" picks x86-64-v3 (AVX2, FMA, BMI2: Intel Haswell, AMD Excavator and later) where
# the compiler has it and the configuring machine runs it. On the Cornell boxes it renders
# 5-8 % faster than the x86-64 baseline, and faster than -march=native (with AVX-512) on an
# AMD EPYC (docs/benchmarks.md, stop 38). The renderer refuses a CPU that lacks what it was built for
# with a message rather than an illegal instruction (cmd/cpucheck.cpp): a study's workers on
# other machines need a build of their own, or PBRT_EXT_TARGET_ARCH=none.
#
# -ffp-contract=off whatever the target: without it the compiler fuses a * b + c into one
# rounding where FMA exists, and images would depend on the machine that built the renderer.
# With it they are bit-identical across targets; FMA serves std::fma (DifferenceOfProducts)
# inline instead of through libm.

set(PBRT_EXT_TARGET_ARCH "auto" CACHE STRING
    "-march= for every target: auto (x86-64-v3 where the compiler and this machine have it), none (the compiler's default), or any -march value such as native")

add_compile_options(-ffp-contract=off)

include(CheckCXXCompilerFlag)

function(pbrt_ext_resolve_target_arch out)
  if(PBRT_EXT_TARGET_ARCH STREQUAL "none")
    set(${out} "none" PARENT_SCOPE)
    return()
  endif()
  if(NOT PBRT_EXT_TARGET_ARCH STREQUAL "auto")
    # A value the compiler rejects fails here, naming the option, not at the first compile.
    check_cxx_compiler_flag(-march=${PBRT_EXT_TARGET_ARCH} PBRT_EXT_COMPILER_HAS_TARGET_ARCH)
    if(NOT PBRT_EXT_COMPILER_HAS_TARGET_ARCH)
      unset(PBRT_EXT_COMPILER_HAS_TARGET_ARCH CACHE)
      message(FATAL_ERROR "PBRT_EXT_TARGET_ARCH=${PBRT_EXT_TARGET_ARCH}: ${CMAKE_CXX_COMPILER} "
                          "does not accept -march=${PBRT_EXT_TARGET_ARCH} (use auto, none or a "
                          "-march value it knows)")
    endif()
    unset(PBRT_EXT_COMPILER_HAS_TARGET_ARCH CACHE)
    set(${out} "${PBRT_EXT_TARGET_ARCH}" PARENT_SCOPE)
    return()
  endif()
  set(${out} "none" PARENT_SCOPE)
  if(NOT CMAKE_SYSTEM_PROCESSOR MATCHES "^(x86_64|AMD64)$" OR CMAKE_CROSSCOMPILING)
    return()
  endif()
  check_cxx_compiler_flag(-march=x86-64-v3 PBRT_EXT_COMPILER_HAS_X86_64_V3)
  if(NOT PBRT_EXT_COMPILER_HAS_X86_64_V3)
    return()
  endif()
  set(probe ${CMAKE_CURRENT_BINARY_DIR}/CMakeFiles/cpu_has_x86_64_v3.cpp)
  file(WRITE ${probe} [=[
int main() {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                   __builtin_cpu_supports("bmi2") ? 0 : 1;
}
]=])
  try_run(PBRT_EXT_X86_64_V3_RUNS PBRT_EXT_X86_64_V3_COMPILES ${CMAKE_CURRENT_BINARY_DIR}/CMakeFiles/cpu_has_x86_64_v3 ${probe})
  if(PBRT_EXT_X86_64_V3_COMPILES AND PBRT_EXT_X86_64_V3_RUNS EQUAL 0)
    set(${out} "x86-64-v3" PARENT_SCOPE)
  endif()
endfunction()

pbrt_ext_resolve_target_arch(PBRT_EXT_MARCH)
if(PBRT_EXT_MARCH STREQUAL "none")
  message(STATUS "pbrt_ext: the compiler's default target (PBRT_EXT_TARGET_ARCH=${PBRT_EXT_TARGET_ARCH})")
else()
  message(STATUS "pbrt_ext: -march=${PBRT_EXT_MARCH} (PBRT_EXT_TARGET_ARCH=${PBRT_EXT_TARGET_ARCH})")
  add_compile_options(-march=${PBRT_EXT_MARCH})
endif()
