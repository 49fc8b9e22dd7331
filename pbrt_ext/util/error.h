// User-facing errors and warnings about input files, located as "file:line:col" (host only).
//
// Every reader of user input (the scene parser, the parameter dictionary, PLY and image
// loaders) reports bad input by throwing ParseError, whose what() is the complete message
// "file:line:col: error: ...", so that the command line prints it verbatim and tests can
// assert the exact text. Problems that do not stop a render (unsupported features) go
// through WarningAt, which shares util/log.h's quiet switch and warning count.
#pragma once

#include "pbrt_ext/util/log.h"

#include <fmt/format.h>

#include <cstdarg>
#include <cstdio>
#include <stdexcept>
#include <string>

namespace pbrt {

// A position in an input file; line and column count from 1, as editors show them. A line or
// column of 0 means "not meaningful" (a whole-file problem, a binary body) and is left out of
// ToString(): "file", "file:line" or "file:line:col".
struct FileLoc {
    std::string filename;
    int line = 1, column = 1;

    // fmt, not string concatenation: GCC 12 warns falsely (-Wrestrict) on the latter at -O3.
    std::string ToString() const {
        if (line <= 0)
            return filename;
        return column > 0 ? fmt::format("{}:{}:{}", filename, line, column)
                          : fmt::format("{}:{}", filename, line);
    }
};

class ParseError : public std::runtime_error {
  public:
    ParseError(const FileLoc &loc, const std::string &message)
        : std::runtime_error(fmt::format("{}: error: {}", loc.ToString(), message)), loc(loc) {}

    FileLoc loc;
};

// A problem with a whole file (an image, a film slice), where no line means anything: a
// std::runtime_error "<path>: error: <what>", which the command line prints as it is.
[[noreturn]] inline void ThrowFileError(const std::string &path, const std::string &what) {
    throw std::runtime_error(path + ": error: " + what);
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
inline void WarningAt(const FileLoc &loc, const char *fmt, ...) {
    // Formatted here rather than forwarded to Warning(), whose "warning: " prefix would come
    // before the location; the quiet switch and the count are Warning()'s own.
    ++Log().warnings;
    if (Log().quiet)
        return;
    std::va_list args;
    va_start(args, fmt);
    std::fprintf(stderr, "%s: warning: ", loc.ToString().c_str());
    std::vfprintf(stderr, fmt, args);
    std::fputc('\n', stderr);
    va_end(args);
}

}  // namespace pbrt
