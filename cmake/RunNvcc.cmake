# Build step of a CUDA compile check, run as
#   cmake -DNVCC=... -DHOST_COMPILER=... -DINCLUDE_DIR=... -DSOURCE=... -DOBJECT=<the .ptx>
#         -DDEPFILE=... -DLOG=... -P RunNvcc.cmake
# It always succeeds: the verdict goes to LOG, whose last line the ctest matches, so a
# broken toolkit fails that test and leaves the rest of the build alone.

# Calling host-only code from a PBRT_CPU_GPU function is only a warning in nvcc until
# device code reaches it; as an error it catches a header that is not GPU-clean even
# where this kernel does not exercise the offending path. The check stops at PTX: the device
# front end and code generation are what prove a header GPU-clean, and ptxas, which turns PTX into
# machine code, took most of the time (the transmission kernel: 64 s to an object, 14 s to PTX).
set(command
    ${NVCC} -std=c++20 --expt-relaxed-constexpr
    -Werror cross-execution-space-call
    -ccbin ${HOST_COMPILER}
    -I${INCLUDE_DIR}
    -MD -MF ${DEPFILE} -MT ${LOG}
    --ptx ${SOURCE} -o ${OBJECT})

execute_process(COMMAND ${command}
                RESULT_VARIABLE result
                OUTPUT_VARIABLE output
                ERROR_VARIABLE output)

if(result STREQUAL "0")
  set(verdict "CUDA compile check passed: ${SOURCE}")
else()
  set(verdict "CUDA compile check failed (nvcc: ${result}): ${SOURCE}")
  message(WARNING "${output}${verdict}")
  file(REMOVE ${OBJECT})
  # The build system requires a dependency file; keep the check re-running on edits
  # to the source even when nvcc died before writing one.
  if(NOT EXISTS ${DEPFILE})
    file(WRITE ${DEPFILE} "${LOG}: ${SOURCE}\n")
  endif()
endif()

list(JOIN command " " command_line)
file(WRITE ${LOG} "${command_line}\n${output}${verdict}\n")
