// For the build tools that generate tables (rgb2spec_opt, sampletables_gen): writing a file so
// that an interrupted run leaves nothing a later build would take for finished, and the C++
// source that embeds a binary file with the assembler's .incbin, since millions of numbers as
// C++ text would take the compiler far longer to parse than the tools take to compute them.
#pragma once

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

namespace pbrt::embedded {

// Writes through a temporary file and renames it.
inline bool WriteFile(const std::filesystem::path &path, const void *data, size_t size) {
    std::filesystem::path tmp = path;
    tmp += ".tmp";
    std::error_code ec;
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path(), ec);
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        if (!out.write(static_cast<const char *>(data), std::streamsize(size))) return false;
    }
    std::filesystem::rename(tmp, path, ec);
    if (ec) std::filesystem::remove(tmp, ec);
    return !ec;
}

// Quotes a path for the assembler's .incbin.
inline std::string AssemblerString(const std::string &s) {
    std::string q = "\\\"";
    for (char c : s) {
        if (c == '"' || c == '\\') q += "\\\\\\";
        q += c;
    }
    return q + "\\\"";
}

// C++ source defining the extern "C" read-only symbol `symbol` as the bytes of `bin`, aligned
// to 64 bytes. The source names the file, so write the file first.
inline std::string IncbinDefinition(const std::string &symbol, const std::filesystem::path &bin,
                                    size_t bytes) {
    return "asm(\".pushsection .rodata\\n\"\n"
           "    \".balign 64\\n\"\n"
           "    \".globl " + symbol + "\\n\"\n"
           "    \".type " + symbol + ", %object\\n\"\n"
           "    \"" + symbol + ":\\n\"\n"
           "    \".incbin " + AssemblerString(std::filesystem::absolute(bin).string()) + "\\n\"\n"
           "    \".size " + symbol + ", " + std::to_string(bytes) + "\\n\"\n"
           "    \".popsection\\n\");\n";
}

}  // namespace pbrt::embedded
