// Image resampling for texture pyramids: pbrt-v4's Image::FloatResizeUp and
// Image::GeneratePyramid. The same resampling weights and the same 2x2 averages as pbrt-v4, so
// that a texture lookup reads pbrt-v4's texel values.
#include "pbrt_ext/images/image.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace pbrt {

namespace {

// The four source pixels around an output pixel and their normalized weights.
struct ResampleWeight {
    int firstPixel;
    Float weight[4];
};

std::vector<ResampleWeight> ResampleWeights(int oldRes, int newRes) {
    constexpr Float filterRadius = 2, tau = 2;
    std::vector<ResampleWeight> weights(static_cast<size_t>(newRes));
    for (int i = 0; i < newRes; ++i) {
        ResampleWeight &w = weights[size_t(i)];
        Float center = (Float(i) + .5f) * Float(oldRes) / Float(newRes);
        w.firstPixel = int(std::floor((center - filterRadius) + 0.5f));
        Float sum = 0;
        for (int j = 0; j < 4; ++j)
            sum += w.weight[j] = WindowedSinc(Float(w.firstPixel + j) + .5f - center, filterRadius, tau);
        for (Float &wj : w.weight) wj /= sum;
    }
    return weights;
}

// Both sides powers of two.
bool IsPowerOf2(Point2i res) {
    return std::has_single_bit(unsigned(res.x)) && std::has_single_bit(unsigned(res.y));
}

}  // namespace

Image Image::FloatResizeUp(Point2i newRes, WrapMode2D wrapMode) const {
    if (newRes.x < resolution.x || newRes.y < resolution.y)
        throw std::invalid_argument("Image::FloatResizeUp: the new resolution is smaller");
    std::vector<ResampleWeight> xWeights = ResampleWeights(resolution.x, newRes.x);
    std::vector<ResampleWeight> yWeights = ResampleWeights(resolution.y, newRes.y);
    // Rows first, into an image as wide as the result and as tall as this one; pbrt-v4 clamps
    // the negative lobes only after the second pass.
    Image rows(Point2i(newRes.x, resolution.y));
    tbb::parallel_for(0, resolution.y, [&](int y) {
        for (int x = 0; x < newRes.x; ++x) {
            const ResampleWeight &w = xWeights[size_t(x)];
            RGB v;
            for (int j = 0; j < 4; ++j) v += w.weight[j] * GetChannels(Point2i(w.firstPixel + j, y), wrapMode);
            rows.SetRGB(Point2i(x, y), v);
        }
    });
    Image result(newRes);
    result.colorSpace = colorSpace;
    tbb::parallel_for(0, newRes.y, [&](int y) {
        const ResampleWeight &w = yWeights[size_t(y)];
        for (int x = 0; x < newRes.x; ++x) {
            RGB v;
            for (int j = 0; j < 4; ++j) v += w.weight[j] * rows.GetChannels(Point2i(x, w.firstPixel + j), wrapMode);
            result.SetRGB(Point2i(x, y), ClampZero(v));
        }
    });
    return result;
}

Image Image::HalfResolution() const {
    Point2i next(std::max(1, resolution.x / 2), std::max(1, resolution.y / 2));
    Image half(next);
    half.colorSpace = colorSpace;
    tbb::parallel_for(0, next.y, [&](int y) {
        // A side of one texel has no second texel to average.
        int y0 = 2 * y, y1 = std::min(2 * y + 1, resolution.y - 1);
        for (int x = 0; x < next.x; ++x) {
            int x0 = 2 * x, x1 = std::min(2 * x + 1, resolution.x - 1);
            RGB v = (GetChannels(Point2i(x0, y0)) + GetChannels(Point2i(x1, y0)) +
                     GetChannels(Point2i(x0, y1)) + GetChannels(Point2i(x1, y1))) / 4;
            half.SetRGB(Point2i(x, y), v);
        }
    });
    return half;
}

Image Image::EncodedAs8Bit(ColorEncoding encoding, int channels) const {
    Image image;
    image.resolution = resolution;
    image.colorSpace = colorSpace;
    image.byteChannels = channels;
    image.SetByteEncoding(encoding);
    size_t n = size_t(resolution.x) * size_t(resolution.y);
    image.bytes.resize(n * size_t(channels));
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < channels; ++c)
            image.bytes[i * size_t(channels) + size_t(c)] = encoding.ToByte(pixels[3 * i + size_t(c)]);
    return image;
}

Image Image::AsFloat() const {
    if (!Is8Bit()) return *this;
    Image image;
    image.resolution = resolution;
    image.colorSpace = colorSpace;
    image.pixels = DecodeBytes();
    return image;
}

std::vector<Image> Image::GeneratePyramid(Image image, WrapMode2D wrapMode) {
    if (image.Empty()) throw std::invalid_argument("Image::GeneratePyramid: the image has no pixels");
    bool is8Bit = image.Is8Bit();
    ColorEncoding encoding = image.byteEncoding;
    int byteChannels = image.byteChannels;
    auto stored = [&](const Image &level) {
        return is8Bit ? level.EncodedAs8Bit(encoding, byteChannels) : level;
    };
    std::vector<Image> pyramid;
    Image level;  // float RGB, halved at each step
    if (!IsPowerOf2(image.resolution)) {
        level = image.FloatResizeUp(Point2i(int(std::bit_ceil(unsigned(image.resolution.x))),
                                            int(std::bit_ceil(unsigned(image.resolution.y)))),
                                    wrapMode);
        pyramid.push_back(stored(level));
    } else {
        // Already a power of two: level 0 is the image itself (its bytes are what encoding
        // them again would give).
        level = image.AsFloat();
        pyramid.push_back(std::move(image));
    }
    int nLevels = std::bit_width(unsigned(std::max(level.resolution.x, level.resolution.y)));  // 1 + log2
    pyramid.reserve(size_t(nLevels));
    for (int i = 1; i < nLevels; ++i) {
        level = level.HalfResolution();
        pyramid.push_back(stored(level));
    }
    return pyramid;
}

}  // namespace pbrt
