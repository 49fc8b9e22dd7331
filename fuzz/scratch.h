// A scratch directory per process for harnesses that need files: the image and scene targets'
// input files, and the folder against which the parser resolves relative Includes, so that a
// fuzzed Include or file name finds nothing of the user's (absolute paths still reach the real
// file system, read-only). Created empty on first use under the system's temporary directory and
// removed at normal exit.
#pragma once

#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <string_view>

namespace pbrt::fuzz {

// <temp>/pbrt_ext_fuzz_<unique>/<purpose>, created if needed.
std::filesystem::path ScratchDirectory(std::string_view purpose);

// Writes bytes to the file `name` in ScratchDirectory(purpose), replacing it; returns its path.
std::string WriteScratchFile(std::string_view purpose, const std::string &name,
                             std::span<const uint8_t> bytes);

}  // namespace pbrt::fuzz
