#include "pbrt_ext/film/filters.h"

#include <fmt/format.h>

namespace pbrt {

std::string BoxFilter::ToString() const {
    return fmt::format("[ BoxFilter radius: [ {}, {} ] ]", radius.x, radius.y);
}
std::string GaussianFilter::ToString() const {
    return fmt::format("[ GaussianFilter radius: [ {}, {} ] sigma: {} ]", radius.x, radius.y,
                       sigma);
}
std::string MitchellFilter::ToString() const {
    return fmt::format("[ MitchellFilter radius: [ {}, {} ] b: {} c: {} ]", radius.x, radius.y,
                       b, c);
}
std::string TriangleFilter::ToString() const {
    return fmt::format("[ TriangleFilter radius: [ {}, {} ] ]", radius.x, radius.y);
}

}  // namespace pbrt
