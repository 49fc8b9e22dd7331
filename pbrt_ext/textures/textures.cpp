#include "pbrt_ext/textures/textures.h"

#include "pbrt_ext/spectra/colorspace.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <tuple>
#include <utility>

namespace pbrt {

namespace {

// The 1D checks (+1 on even squares, -1 on odd ones) integrated against a tent of radius r
// around x. d is their second antiderivative, so that the tent's integral is the second
// difference of d over [x - r, x + r].
Float FilteredChecks(Float x, Float r) {
    if (std::floor(x - r) == std::floor(x + r)) return 1 - 2 * (int(std::floor(x)) & 1);
    auto d = [](Float v) {
        Float y = v / 2 - std::floor(v / 2) - 0.5f;
        return v / 2 + y * (1 - 2 * std::abs(y));
    };
    return (d(x + r) - 2 * d(x) + d(x - r)) / Sqr(r);
}

// The tent's radius on one axis: 1.5 times the footprint's larger extent along it.
Float TentRadius(Float dx, Float dy) {
    return 1.5f * std::max(std::abs(dx), std::abs(dy));
}

}  // namespace

Float Checkerboard(const TextureMapping2D &mapping, const TextureEvalContext &ctx) {
    TexCoord2D c = mapping.Map(ctx);
    return 0.5f - FilteredChecks(c.st[0], TentRadius(c.dsdx, c.dsdy)) *
                      FilteredChecks(c.st[1], TentRadius(c.dtdx, c.dtdy)) / 2;
}

Float Checkerboard(const TextureMapping3D &mapping, const TextureEvalContext &ctx) {
    TexCoord3D c = mapping.Map(ctx);
    Float product = 1;
    for (int i = 0; i < 3; ++i) product *= FilteredChecks(c.p[i], TentRadius(c.dpdx[i], c.dpdy[i]));
    return 0.5f - product / 2;
}

RGB ImageTextureBase::ScaledLookup(const TextureEvalContext &ctx) const {
    TexCoord2D c = mapping.Map(ctx);
    c.st[1] = 1 - c.st[1];
    return scale * mipmap->Filter(c.st, Vector2f(c.dsdx, -c.dtdx), Vector2f(c.dsdy, -c.dtdy));
}

Float FloatImageTexture::Evaluate(const TextureEvalContext &ctx) const {
    Float v = ScaledLookup(ctx).Average();
    return invert ? std::max<Float>(0, 1 - v) : v;
}

SampledSpectrum SpectrumImageTexture::Evaluate(const TextureEvalContext &ctx,
                                               const SampledWavelengths &lambda) const {
    RGB rgb = ScaledLookup(ctx);
    if (invert) rgb = RGB(1 - rgb.r, 1 - rgb.g, 1 - rgb.b);
    rgb = RGB(std::max<Float>(0, rgb.r), std::max<Float>(0, rgb.g), std::max<Float>(0, rgb.b));
    const RGBColorSpace &cs = mipmap->ColorSpace();
    switch (type) {
    case SpectrumType::Albedo:
        rgb = RGB(std::min<Float>(1, rgb.r), std::min<Float>(1, rgb.g), std::min<Float>(1, rgb.b));
        return RGBAlbedoSpectrum(cs, rgb).Sample(lambda);
    case SpectrumType::Unbounded:
        return RGBUnboundedSpectrum(cs, rgb).Sample(lambda);
    case SpectrumType::Illuminant:
        return RGBIlluminantSpectrum(cs, rgb).Sample(lambda);
    }
    return SampledSpectrum(0.f);
}

namespace {

// Values made once per key, outside the lock so that different files load in parallel; if two
// threads race on one key, the first insertion wins and both get the same value.
template <typename Key, typename Value>
class OnceCache {
  public:
    template <typename Make>
    std::shared_ptr<const Value> Get(const Key &key, Make make) {
        {
            std::lock_guard<std::mutex> lock(mutex);
            if (auto it = values.find(key); it != values.end()) return it->second;
        }
        auto value = std::make_shared<const Value>(make());
        std::lock_guard<std::mutex> lock(mutex);
        return values.emplace(key, std::move(value)).first->second;
    }
    void Clear() {
        std::lock_guard<std::mutex> lock(mutex);
        values.clear();
    }

  private:
    std::mutex mutex;
    std::map<Key, std::shared_ptr<const Value>> values;
};

using ImageKey = std::pair<std::string, std::string>;  // file, encoding
// The file, its encoding, wrap, filter, anisotropy, channels and averageOnly.
using MIPMapKey = std::tuple<std::string, std::string, int, int, Float, int, bool>;

OnceCache<ImageKey, Image> &Images() {
    static OnceCache<ImageKey, Image> images;
    return images;
}

OnceCache<MIPMapKey, MIPMap> &MIPMaps() {
    static OnceCache<MIPMapKey, MIPMap> mipmaps;
    return mipmaps;
}

}  // namespace

std::shared_ptr<const Image> ImageTextureCache::Get(const std::string &filename,
                                                   ColorEncoding encoding) {
    return Images().Get(ImageKey(filename, encoding.ToString()),
                        [&] { return Image::Read(filename, encoding); });
}

std::shared_ptr<const MIPMap> ImageTextureCache::GetMIPMap(const std::string &filename,
                                                          ColorEncoding encoding, WrapMode wrapMode,
                                                          MIPMapFilterOptions options,
                                                          ImageChannels channels) {
    MIPMapKey key(filename, encoding.ToString(), int(wrapMode), int(options.filter),
                  options.maxAnisotropy, int(channels), options.averageOnly);
    return MIPMaps().Get(key, [&] {
        return MIPMap(Image::Read(filename, encoding, channels), wrapMode, options);
    });
}

void ImageTextureCache::Clear() {
    Images().Clear();
    MIPMaps().Clear();
}

pstd::optional<WrapMode> ParseWrapMode(const std::string &name) {
    if (name == "repeat") return WrapMode::Repeat;
    if (name == "clamp") return WrapMode::Clamp;
    if (name == "black") return WrapMode::Black;
    if (name == "octahedralsphere") return WrapMode::OctahedralSphere;
    return {};
}

}  // namespace pbrt
