#include "fuzz/scratch.h"

#include <stdlib.h>

#include <fstream>
#include <stdexcept>
#include <string>
#include <system_error>

namespace pbrt::fuzz {

namespace {

// mkdtemp, not a name built from the process id: several fuzzers and tests run at once.
class ScratchRoot {
  public:
    ScratchRoot() {
        std::string pattern = (std::filesystem::temp_directory_path() / "pbrt_ext_fuzz_XXXXXX").string();
        if (!mkdtemp(pattern.data()))
            throw std::system_error(errno, std::generic_category(), "mkdtemp " + pattern);
        root = pattern;
    }
    ~ScratchRoot() {
        std::error_code ignored;
        std::filesystem::remove_all(root, ignored);
    }
    ScratchRoot(const ScratchRoot &) = delete;
    ScratchRoot &operator=(const ScratchRoot &) = delete;

    std::filesystem::path root;
};

}  // namespace

std::filesystem::path ScratchDirectory(std::string_view purpose) {
    static ScratchRoot scratch;
    std::filesystem::path dir = scratch.root / purpose;
    std::filesystem::create_directories(dir);
    return dir;
}

std::string WriteScratchFile(std::string_view purpose, const std::string &name,
                             std::span<const uint8_t> bytes) {
    std::string path = (ScratchDirectory(purpose) / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char *>(bytes.data()), std::streamsize(bytes.size()));
    out.close();
    // A harness that cannot write its input tests nothing: stop rather than report false passes.
    if (!out)
        throw std::system_error(errno, std::generic_category(), "cannot write " + path);
    return path;
}

}  // namespace pbrt::fuzz
