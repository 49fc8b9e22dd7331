// Small text helpers shared by the command line and the scene format.
#pragma once

#include <cctype>
#include <charconv>
#include <string>
#include <string_view>

namespace pbrt {

// pbrt-v4 matches option names, on its command line and in Option directives, ignoring case,
// '-' and '_' ("--Disable_Pixel-Jitter" is "disablepixeljitter").
inline std::string NormalizeOptionName(std::string_view name) {
    std::string n;
    for (char c : name)
        if (c != '-' && c != '_') n += char(std::tolower((unsigned char)c));
    return n;
}

// Whether the whole text is one number, as std::from_chars reads a double.
inline bool IsNumberText(std::string_view text) {
    double v;
    auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    return !text.empty() && ec == std::errc() && ptr == text.data() + text.size();
}

}  // namespace pbrt
