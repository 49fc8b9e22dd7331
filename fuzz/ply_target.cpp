// The ply target: a PLY file decoded in memory.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"

#include "pbrt_ext/util/ply.h"

#include <string_view>

namespace pbrt::fuzz {

void FuzzPly(std::span<const uint8_t> data) {
    std::string_view contents(reinterpret_cast<const char *>(data.data()), data.size());
    ExpectReadOrRejection("ply", [&] { ParsePly(contents, "input.ply"); });
}

}  // namespace pbrt::fuzz
