# libFuzzer builds (PBRT_EXT_BUILD_FUZZERS, the `fuzz` preset, scripts/fuzz): clang only.
#
# Coverage instrumentation (-fsanitize=fuzzer-no-link) is applied globally, as the sanitizers are:
# libFuzzer is guided by the edges of the library code a harness reaches, not by the harness alone.
# Only the fuzzer executables link libFuzzer itself (-fsanitize=fuzzer, which brings its main()),
# through pbrt_ext_add_fuzzer() in fuzz/CMakeLists.txt.

if(PBRT_EXT_BUILD_FUZZERS)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR
            "PBRT_EXT_BUILD_FUZZERS needs clang for libFuzzer, but the C++ compiler is "
            "${CMAKE_CXX_COMPILER_ID} ${CMAKE_CXX_COMPILER}. Configure a fresh build directory "
            "with the fuzz preset (cmake --preset fuzz) or -DCMAKE_CXX_COMPILER=clang++.")
  endif()
  add_compile_options(-fsanitize=fuzzer-no-link)
endif()
