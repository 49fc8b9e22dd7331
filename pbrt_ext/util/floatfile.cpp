#include "pbrt_ext/util/floatfile.h"

#include "pbrt_ext/util/resourcelimits.h"

#include <cmath>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <sstream>

namespace pbrt {

std::vector<double> ReadFloatFile(const std::string &path, const FileLoc &loc,
                                  const std::string &what, const std::string &expected) {
    std::optional<uint64_t> size = RegularFileSize(path, nullptr);
    std::ifstream in;
    if (size) in.open(path);  // never a device or pipe, which may never end
    if (!in.is_open()) throw ParseError(loc, what + " cannot be read, expected a file of " + expected);
    CheckMemory(loc, "parsing " + what, SaturatingProduct({*size, kParsedTextBytesPerByte}));
    std::vector<double> numbers;
    std::string line;
    for (int lineNo = 1; std::getline(in, line); ++lineNo) {
        std::istringstream tokens(line.substr(0, line.find('#')));
        std::string token;
        while (tokens >> token) {
            char *end = nullptr;
            double v = std::strtod(token.c_str(), &end);
            if (*end != '\0' || !std::isfinite(v))
                throw ParseError(loc, what + " line " + std::to_string(lineNo) + ": \"" + token +
                                          "\" is not a number, expected " + expected);
            numbers.push_back(v);
        }
    }
    return numbers;
}

}  // namespace pbrt
