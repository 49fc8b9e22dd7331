// libFuzzer entry point of the parser target (fuzz_targets.h).
#include "fuzz/fuzz_targets.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    pbrt::fuzz::FuzzParser({data, size});
    return 0;
}
