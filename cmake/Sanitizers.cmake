# Optional runtime checking of the whole build (the `asan` preset turns it on).
#
# Applied globally rather than per target: a sanitizer must see every object that
# shares memory with the code it checks, test harness included.

set(PBRT_EXT_SANITIZERS "" CACHE STRING
    "Comma-separated -fsanitize= list for every target, e.g. address,undefined (empty: none)")

if(PBRT_EXT_SANITIZERS)
  # Stop at the first report: a test that continues after undefined behaviour proves nothing.
  add_compile_options(-fsanitize=${PBRT_EXT_SANITIZERS} -fno-sanitize-recover=all
                      -fno-omit-frame-pointer)
  add_link_options(-fsanitize=${PBRT_EXT_SANITIZERS})
endif()
