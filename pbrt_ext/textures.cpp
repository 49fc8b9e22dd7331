#include "pbrt_ext/textures.h"

#include "pbrt_ext/util/colorspace.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <mutex>
#include <utility>

namespace pbrt {

RGB ImageTextureBase::ScaledLookup(const TextureEvalContext &ctx) const {
    Point2f st = mapping.Map(ctx);
    st[1] = 1 - st[1];
    if (filter == ImageFilter::Bilinear) return scale * image->Bilerp(st, wrapMode);
    // The texel containing st; floor, not truncation, so that repeat works left of zero.
    Point2i res = image->Resolution();
    Point2i p(int(std::floor(st[0] * res.x)), int(std::floor(st[1] * res.y)));
    return scale * image->GetChannels(p, wrapMode);
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
    const RGBColorSpace &cs = colorSpace ? *colorSpace : RGBColorSpace::sRGB();
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

struct CacheState {
    std::mutex mutex;
    std::map<std::pair<std::string, std::string>, std::shared_ptr<const Image>> images;
};

CacheState &Cache() {
    static CacheState cache;
    return cache;
}

}  // namespace

std::shared_ptr<const Image> ImageTextureCache::Get(const std::string &filename,
                                                   ColorEncoding encoding) {
    CacheState &cache = Cache();
    auto key = std::make_pair(filename, encoding.ToString());
    {
        std::lock_guard<std::mutex> lock(cache.mutex);
        if (auto it = cache.images.find(key); it != cache.images.end()) return it->second;
    }
    // Decoded outside the lock so that different files load in parallel; if two threads race
    // on the same file, the first insertion wins and both get the same image.
    auto image = std::make_shared<const Image>(Image::Read(filename, encoding));
    std::lock_guard<std::mutex> lock(cache.mutex);
    return cache.images.emplace(key, std::move(image)).first->second;
}

void ImageTextureCache::Clear() {
    std::lock_guard<std::mutex> lock(Cache().mutex);
    Cache().images.clear();
}

pstd::optional<WrapMode> ParseWrapMode(const std::string &name) {
    if (name == "repeat") return WrapMode::Repeat;
    if (name == "clamp") return WrapMode::Clamp;
    if (name == "black") return WrapMode::Black;
    if (name == "octahedralsphere") return WrapMode::OctahedralSphere;
    return {};
}

}  // namespace pbrt
