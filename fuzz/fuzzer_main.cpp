// The libFuzzer entry point of one target (fuzz_targets.h): CMake compiles this file once per
// target with PBRT_EXT_FUZZ_TARGET set to its name.
#include "fuzz/fuzz_targets.h"

#include <algorithm>
#include <iterator>

namespace {

constexpr const pbrt::fuzz::FuzzTarget &TargetNamed(std::string_view name) {
    return *std::find_if(std::begin(pbrt::fuzz::kFuzzTargets), std::end(pbrt::fuzz::kFuzzTargets),
                         [&](const pbrt::fuzz::FuzzTarget &t) { return t.name == name; });
}

constexpr const pbrt::fuzz::FuzzTarget &kTarget = TargetNamed(PBRT_EXT_FUZZ_TARGET);

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    kTarget.run({data, size});
    return 0;
}
