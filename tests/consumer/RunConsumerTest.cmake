# ctest's consumer test (cmake -P): installs the build tree into a fresh prefix with
# `cmake --install`, configures and builds tests/consumer against it through find_package(pbrt_ext),
# and runs both of its programs. Any failing step fails the test with that step's output.
# -DBUILD_DIR (pbrt_ext's build tree), -DSOURCE_DIR (tests/consumer), -DWORK_DIR (scratch).
function(run_step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result OUTPUT_VARIABLE out ERROR_VARIABLE out)
  message("${out}")
  if(NOT result EQUAL 0)
    message(FATAL_ERROR "consumer test: ${what} failed (${result})")
  endif()
endfunction()

file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/install)
run_step("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix})
foreach(required bin/pbrt_ext include/pbrt_ext/bxdfs/fabric.h lib/cmake/pbrt_ext/pbrt_extConfig.cmake)
  if(NOT EXISTS ${prefix}/${required})
    message(FATAL_ERROR "consumer test: the install tree has no ${required}")
  endif()
endforeach()
run_step("configuring the consumer" ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${WORK_DIR}/build -G Ninja
         -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run_step("building the consumer" ${CMAKE_COMMAND} --build ${WORK_DIR}/build)
run_step("fabric_consumer" ${WORK_DIR}/build/fabric_consumer)
run_step("library_consumer" ${WORK_DIR}/build/library_consumer ${SOURCE_DIR}/furnace.pbrt)
run_step("the installed pbrt_ext" ${prefix}/bin/pbrt_ext --help)
