// libFuzzer entry point of the ply target (fuzz_targets.h).
#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    pbrt::fuzz::FuzzPly({data, size});
    return 0;
}
