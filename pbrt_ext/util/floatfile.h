// Files of numbers (pbrt-v4's ReadFloatFile): whitespace-separated numbers, '#' comments to
// the end of a line. Spectrum files (.spd) and lens descriptions (.dat) are such files.
#pragma once

#include "pbrt_ext/util/error.h"

#include <string>
#include <vector>

namespace pbrt {

// The numbers of the file at path. A file that cannot be read, or a token that is not a finite
// number, throws ParseError at loc (the scene parameter naming the file), naming `what` (e.g.
// "lens file \"x.dat\"") with the file's line and what the file should hold (`expected`).
std::vector<double> ReadFloatFile(const std::string &path, const FileLoc &loc,
                                  const std::string &what, const std::string &expected);

}  // namespace pbrt
