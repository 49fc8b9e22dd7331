// What the harnesses accept and what they report (fuzz_targets.h).
#pragma once

#include "pbrt_ext/util/resourcelimits.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <string_view>

namespace pbrt::fuzz {

// A violated invariant: printed, then std::abort(), which libFuzzer records as a crash and saves the
// input for; the regression test dies the same way.
[[noreturn]] inline void ReportFinding(std::string_view target, const std::string &what) {
    std::fprintf(stderr, "fuzz finding (%.*s): %s\n", int(target.size()), target.data(),
                 what.c_str());
    std::abort();
}

// The memory one allocation of a reader may take (util/resourcelimits.h) while fuzzed: a quarter of
// scripts/fuzz's -rss_limit_mb, so that a file asking for more meets the resource guards' error,
// and libFuzzer's out-of-memory report can only mean an allocation that no guard checked.
constexpr uint64_t kFuzzMemoryBudget = uint64_t(512) << 20;

// Runs read() within kFuzzMemoryBudget. Its promised answer to bad input is a ParseError or
// std::runtime_error saying "<file[:line:col]>: error: <what>". An exception of another type
// escapes (std::terminate); one without a located message is a finding, because the user would
// not learn where the problem is.
template <typename ReadFn>
void ExpectReadOrRejection(std::string_view target, ReadFn read) {
    SetMemoryBudget(kFuzzMemoryBudget);
    try {
        read();
    } catch (const std::runtime_error &error) {
        if (std::string_view(error.what()).find(": error: ") == std::string_view::npos)
            ReportFinding(target, std::string("error without a location: ") + error.what());
    }
}

}  // namespace pbrt::fuzz
