#include <pbrt_ext/filters.h>

#include <cstdio>

namespace pbrt {

namespace {
std::string Format(const char *fmt, double a, double b, double c = 0, double d = 0) {
    char buf[160];
    std::snprintf(buf, sizeof(buf), fmt, a, b, c, d);
    return buf;
}
}  // namespace

std::string BoxFilter::ToString() const {
    return Format("[ BoxFilter radius: [ %g, %g ] ]", radius.x, radius.y);
}
std::string GaussianFilter::ToString() const {
    return Format("[ GaussianFilter radius: [ %g, %g ] sigma: %g ]", radius.x, radius.y, sigma);
}
std::string MitchellFilter::ToString() const {
    return Format("[ MitchellFilter radius: [ %g, %g ] b: %g c: %g ]", radius.x, radius.y, b, c);
}
std::string TriangleFilter::ToString() const {
    return Format("[ TriangleFilter radius: [ %g, %g ] ]", radius.x, radius.y);
}

}  // namespace pbrt
