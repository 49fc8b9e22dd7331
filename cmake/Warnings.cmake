# Compiler warnings for the project's own targets.
#
# Warnings are applied per target (PRIVATE), never globally, so that they reach our
# sources and headers but not the third-party code we link against. They become errors
# with -DPBRT_EXT_WERROR=ON or whenever the environment variable CI is true, so that
# a continuous-integration run cannot pass with a warning in it.

option(PBRT_EXT_WERROR "Treat compiler warnings as errors" OFF)

set(PBRT_EXT_WARNING_FLAGS
    -Wall
    -Wextra
    -Wpedantic
    # Locals only: pbrt-v4 names constructor parameters after the members they set.
    $<IF:$<CXX_COMPILER_ID:GNU>,-Wshadow=local,-Wshadow-uncaptured-local>
    -Wnon-virtual-dtor
    -Woverloaded-virtual
    -Wcast-align
    -Wformat=2
    -Wimplicit-fallthrough)

# GCC 12 reports false -Wrestrict overlaps inside libstdc++'s std::string operator+ at -O3 (GCC
# bug 105651, fixed in GCC 13): the warning would reject ordinary string building.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND CMAKE_CXX_COMPILER_VERSION VERSION_LESS 13)
  list(APPEND PBRT_EXT_WARNING_FLAGS -Wno-restrict)
endif()

# GCC's flow-based -Wmaybe-uninitialized reports false positives on instrumented code (its
# manual warns that -fsanitize changes what the warning sees), e.g. inside libstdc++'s
# std::regex at -O1: keep it for the uninstrumented builds, where it is reliable.
if(CMAKE_CXX_COMPILER_ID STREQUAL "GNU" AND PBRT_EXT_SANITIZERS)
  list(APPEND PBRT_EXT_WARNING_FLAGS -Wno-maybe-uninitialized)
endif()

# Read at every configure, not cached, so that a build directory configured outside CI
# still turns strict when CI reuses it.
if(PBRT_EXT_WERROR OR "$ENV{CI}")
  list(APPEND PBRT_EXT_WARNING_FLAGS -Werror)
  message(STATUS "pbrt_ext: warnings are errors")
endif()

function(pbrt_ext_enable_warnings target)
  if(CMAKE_CXX_COMPILER_ID MATCHES "GNU|Clang")
    target_compile_options(${target} PRIVATE ${PBRT_EXT_WARNING_FLAGS})
  endif()
endfunction()
