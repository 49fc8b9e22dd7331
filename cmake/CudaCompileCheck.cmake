# CUDA compile checks: prove that GPU-clean headers compile as device code.
#
# No GPU is needed, and CUDA is not a project language: CMake's own CUDA support would
# make a missing or mismatched toolkit a configure or build failure, while here it may
# cost one test at most. The compile runs at build time through RunNvcc.cmake, which
# records its verdict in a log instead of failing; the test reads the verdict.

# Off in the sanitizer preset: device code is the same whatever the host build, so one preset
# checking it is enough, and nvcc is the slowest step of a build.
option(PBRT_EXT_CUDA_COMPILE_CHECKS "Compile-check the GPU-clean headers with nvcc (when found)" ON)

find_program(PBRT_EXT_NVCC nvcc
             HINTS ENV CUDA_PATH ENV CUDA_HOME
             PATH_SUFFIXES bin
             PATHS /usr/local/cuda/bin
             DOC "nvcc for the CUDA compile checks (empty: checks are skipped)")
if(PBRT_EXT_NVCC)
  message(STATUS "CUDA compile checks use ${PBRT_EXT_NVCC}")
else()
  message(STATUS "CUDA compile checks skipped: nvcc not found")
endif()

# pbrt_ext_add_cuda_compile_check(<name> <source.cu>)
# Adds a target and a ctest, both called <name>. The test passes when nvcc compiled
# <source.cu>, fails with nvcc's diagnostics when it did not, and is skipped without nvcc.
function(pbrt_ext_add_cuda_compile_check name source)
  if(NOT PBRT_EXT_CUDA_COMPILE_CHECKS)
    return()
  endif()
  if(NOT PBRT_EXT_NVCC)
    add_test(NAME ${name}
             COMMAND ${CMAKE_COMMAND} -E echo "nvcc not found: CUDA compile check skipped")
    set_tests_properties(${name} PROPERTIES SKIP_REGULAR_EXPRESSION "CUDA compile check skipped")
    return()
  endif()

  cmake_path(ABSOLUTE_PATH source)
  set(log ${CMAKE_CURRENT_BINARY_DIR}/${name}.log)
  set(object ${CMAKE_CURRENT_BINARY_DIR}/${name}.ptx)
  set(depfile ${CMAKE_CURRENT_BINARY_DIR}/${name}.d)
  set(runner ${CMAKE_CURRENT_FUNCTION_LIST_DIR}/RunNvcc.cmake)
  add_custom_command(
    OUTPUT ${log}
    BYPRODUCTS ${object}
    COMMAND ${CMAKE_COMMAND}
            -DNVCC=${PBRT_EXT_NVCC}
            -DHOST_COMPILER=${CMAKE_CXX_COMPILER}
            -DINCLUDE_DIR=${PROJECT_SOURCE_DIR}
            -DSOURCE=${source}
            -DOBJECT=${object}
            -DDEPFILE=${depfile}
            -DLOG=${log}
            -P ${runner}
    DEPENDS ${source} ${runner}
    DEPFILE ${depfile}
    COMMENT "CUDA compile check ${name}"
    VERBATIM)
  add_custom_target(${name} ALL DEPENDS ${log})

  add_test(NAME ${name} COMMAND ${CMAKE_COMMAND} -E cat ${log})
  set_tests_properties(${name} PROPERTIES PASS_REGULAR_EXPRESSION "CUDA compile check passed")
endfunction()
