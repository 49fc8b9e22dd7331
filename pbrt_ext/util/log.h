// Messages for the user: warnings and errors on stderr, printf-style (host only).
//
// Library code reports bad input by throwing at its boundary (parsers, file I/O) and warns through
// Warning(); nothing here aborts. Warnings can be silenced (tests) and are counted.
#pragma once

#include <atomic>
#include <cstdarg>
#include <cstdio>

namespace pbrt {

struct LogState {
    std::atomic<bool> quiet{false};
    std::atomic<int> warnings{0};
};

inline LogState &Log() {
    static LogState state;
    return state;
}

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
inline void Warning(const char *fmt, ...) {
    ++Log().warnings;
    if (Log().quiet)
        return;
    std::va_list args;
    va_start(args, fmt);
    std::fputs("warning: ", stderr);
    std::vfprintf(stderr, fmt, args);
    std::fputc('\n', stderr);
    va_end(args);
}

#if defined(__GNUC__)
__attribute__((format(printf, 1, 2)))
#endif
inline void Error(const char *fmt, ...) {
    std::va_list args;
    va_start(args, fmt);
    std::fputs("error: ", stderr);
    std::vfprintf(stderr, fmt, args);
    std::fputc('\n', stderr);
    va_end(args);
}

}  // namespace pbrt
