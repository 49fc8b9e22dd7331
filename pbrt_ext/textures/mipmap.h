// Image pyramids and their filtered lookups (pbrt-v4's util/mipmap.h): what an image texture
// returns over the footprint of a pixel, given the derivatives of its (s, t) coordinates along
// the pixel's x and y.
//
// The pyramid is pbrt-v4's (Image::GeneratePyramid): the image resampled up to powers of two,
// then halved by 2x2 box filtering down to one texel, each level kept in the texel format of
// the file (8-bit stays 8-bit). The filters are pbrt-v4's: "point", "bilinear" and "trilinear"
// choose a level by the footprint's widest extent, "ewa" filters an ellipse at the level of its
// minor axis. Two differences, both corrections that the tests below pin down:
//  - trilinear blends the two levels around the footprint's level also between levels 0 and
//    1 (pbrt-v4 takes level 0 alone there, sharper than the footprint asks);
//  - EWA weighs texels by the truncated Gaussian itself, exp(-2 r^2) - exp(-2), where pbrt-v4
//    rounds r^2 down to a table of 128 entries.
#pragma once

#include "pbrt_ext/images/image.h"

#include <optional>
#include <string>
#include <vector>

namespace pbrt {

enum class FilterFunction { Point, Bilinear, Trilinear, EWA };

// pbrt-v4's names: "point", "bilinear", "trilinear", "ewa" (or "EWA"); empty otherwise.
std::optional<FilterFunction> ParseFilterFunction(const std::string &name);

struct MIPMapFilterOptions {
    FilterFunction filter = FilterFunction::Bilinear;
    // EWA lengthens the minor axis until the ellipse is at most this eccentric.
    Float maxAnisotropy = 8;
    // Only the pyramid's top texel, the image's average (pbrt-v4's --disable-image-textures).
    bool averageOnly = false;
    friend bool operator==(const MIPMapFilterOptions &, const MIPMapFilterOptions &) = default;
};

class MIPMap {
  public:
    MIPMap(Image image, WrapMode wrapMode, MIPMapFilterOptions options);

    // The filtered RGB at st, over the footprint whose sides are dst0 = (ds/dx, dt/dx) and
    // dst1 = (ds/dy, dt/dy). A zero footprint reads the finest level.
    RGB Filter(Point2f st, Vector2f dst0, Vector2f dst1) const;

    int Levels() const { return int(pyramid.size()); }
    // Level 0 is the finest.
    const Image &Level(int level) const { return pyramid[size_t(level)]; }
    Point2i LevelResolution(int level) const { return Level(level).Resolution(); }

    RGB Texel(int level, Point2i st) const { return Level(level).GetChannels(st, wrapMode); }
    RGB Bilerp(int level, Point2f st) const { return Level(level).Bilerp(st, wrapMode); }
    // The Gaussian-weighted average over the ellipse at level (the top texel above the pyramid).
    RGB EWA(int level, Point2f st, Vector2f dst0, Vector2f dst1) const;

    // The colour space of the source image's RGB, which every level keeps (pbrt-v4's
    // GetRGBColorSpace).
    const RGBColorSpace &ColorSpace() const { return pyramid.front().ColorSpace(); }

  private:
    std::vector<Image> pyramid;
    WrapMode wrapMode;
    MIPMapFilterOptions options;
};

}  // namespace pbrt
