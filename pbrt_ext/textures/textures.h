// Textures: what a material's parameters vary with over a surface (pbrt-v4's src/pbrt/textures.h,
// reduced). The closed sets of float and spectrum textures are the variants of FloatTexture and
// SpectrumTexture; a constant parameter is evaluated without any lookup.
//
// As in pbrt-v4, a texture that combines others (scale, mix, checkerboard) refers to them by
// handle: here a shared, immutable FloatTexture or SpectrumTexture, so that a named texture used
// by many materials exists once and copying a texture is cheap. Textures are host types (image
// pixels live in a std::vector); their Evaluate() never allocates.
//
// Image textures are filtered over the pixel's footprint by a MIPMap (textures/mipmap.h), and the
// checkerboard is box filtered over it as pbrt-v4 does; the footprint comes from the ray
// differentials of the hit (zero where the scene needs none: then the finest level is read).
#pragma once

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/textures/mipmap.h"
#include "pbrt_ext/textures/proceduraltextures.h"
#include "pbrt_ext/textures/texturemappings.h"
#include "pbrt_ext/util/spectrum.h"

#include <memory>
#include <string>
#include <type_traits>
#include <variant>

namespace pbrt {

class FloatTexture;
class SpectrumTexture;

// ---- Constant ---------------------------------------------------------------------------------

struct FloatConstantTexture {
    Float value;
    Float Evaluate(const TextureEvalContext &) const { return value; }
};

struct SpectrumConstantTexture {
    Spectrum value;
    SampledSpectrum Evaluate(const TextureEvalContext &, const SampledWavelengths &lambda) const {
        return value.Sample(lambda);
    }
};

// ---- Scale, mix, checkerboard (one definition for both value types) -------------------------
// A spectrum texture's Evaluate also takes the path's wavelengths; the combining textures pass
// whatever follows the context (nothing, or the wavelengths) on to the textures they combine.

namespace detail {

// tex * scale; tex is not evaluated where the scale is 0 (pbrt-v4's ScaledTexture).
template <typename Tex>
struct ScaledTexture {
    ScaledTexture(Tex tex, FloatTexture scale);
    template <typename... Lambda>
    auto Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const;
    std::shared_ptr<const Tex> tex;
    std::shared_ptr<const FloatTexture> scale;
};

// (1 - amount) tex1 + amount tex2; a texture whose weight is 0 is not evaluated.
template <typename Tex>
struct MixTexture {
    MixTexture(Tex tex1, Tex tex2, FloatTexture amount);
    template <typename... Lambda>
    auto Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const;
    std::shared_ptr<const Tex> tex1, tex2;
    std::shared_ptr<const FloatTexture> amount;
};

// tex1 on the squares of (s, t) (or cubes of texture space) whose integer coordinates have an
// even sum, tex2 on the others.
template <typename Tex>
struct CheckerboardTexture {
    using Mapping = std::variant<TextureMapping2D, TextureMapping3D>;
    CheckerboardTexture(Mapping mapping, Tex tex1, Tex tex2);
    template <typename... Lambda>
    auto Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const;
    Mapping mapping;
    std::shared_ptr<const Tex> tex1, tex2;
};

// inside within pbrt-v4's polka dots (InsidePolkaDot), outside elsewhere.
template <typename Tex>
struct DotsTexture {
    DotsTexture(TextureMapping2D mapping, Tex outside, Tex inside);
    template <typename... Lambda>
    auto Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const;
    TextureMapping2D mapping;
    std::shared_ptr<const Tex> outside, inside;
};

// |n . dir| tex1 + (1 - |n . dir|) tex2: tex1 where the surface faces along dir (a unit vector).
template <typename Tex>
struct DirectionMixTexture {
    DirectionMixTexture(Tex tex1, Tex tex2, Vector3f dir);
    template <typename... Lambda>
    auto Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const;
    std::shared_ptr<const Tex> tex1, tex2;
    Vector3f dir;
};

}  // namespace detail

using FloatScaledTexture = detail::ScaledTexture<FloatTexture>;
using SpectrumScaledTexture = detail::ScaledTexture<SpectrumTexture>;
using FloatMixTexture = detail::MixTexture<FloatTexture>;
using SpectrumMixTexture = detail::MixTexture<SpectrumTexture>;
using FloatCheckerboardTexture = detail::CheckerboardTexture<FloatTexture>;
using SpectrumCheckerboardTexture = detail::CheckerboardTexture<SpectrumTexture>;
using FloatDotsTexture = detail::DotsTexture<FloatTexture>;
using SpectrumDotsTexture = detail::DotsTexture<SpectrumTexture>;
using FloatDirectionMixTexture = detail::DirectionMixTexture<FloatTexture>;
using SpectrumDirectionMixTexture = detail::DirectionMixTexture<SpectrumTexture>;

// The weight of tex2 in CheckerboardTexture: 0 on the squares where it shows tex1, 1 on the
// others, and between them where the pixel's footprint covers both (pbrt-v4's Checkerboard: the
// checks integrated against a filter 1.5 times the footprint's widest extent on each axis).
Float Checkerboard(const TextureMapping2D &mapping, const TextureEvalContext &ctx);
Float Checkerboard(const TextureMapping3D &mapping, const TextureEvalContext &ctx);

// ---- Image maps -------------------------------------------------------------------------------

// What pbrt-v4's ImageTextureBase holds. The pyramid is built once per file, encoding, wrap
// mode and filter, and shared by every texture that reads it (ImageTextureCache).
struct ImageTextureBase {
    TextureMapping2D mapping;
    std::shared_ptr<const MIPMap> mipmap;
    Float scale = 1;
    bool invert = false;

    // scale times the filtered RGB at the mapped point; t is flipped so that t = 0 is the
    // bottom row of the file, as in pbrt-v4 (and so are its derivatives, which pbrt-v4 leaves,
    // mirroring a footprint that is oblique in texture space).
    RGB ScaledLookup(const TextureEvalContext &ctx) const;
};

// The average of the channels, as pbrt-v4 reads an RGB image as a float texture; an RGBA
// file's alpha where it is not 1 everywhere, as pbrt-v4 reads that.
struct FloatImageTexture : ImageTextureBase {
    Float Evaluate(const TextureEvalContext &ctx) const;
};

// The texel's RGB, clamped to >= 0 (and to [0, 1] for an albedo), becomes the RGB spectrum of
// the texture's type in the colour space the image is in (its MIPMap's), at lookup (pbrt-v4's
// SpectrumImageTexture).
struct SpectrumImageTexture : ImageTextureBase {
    SpectrumType type = SpectrumType::Albedo;
    SampledSpectrum Evaluate(const TextureEvalContext &ctx, const SampledWavelengths &lambda) const;
};

// Images decoded for textures (normal maps) and the pyramids of image textures, for the life
// of the program (pbrt-v4 keeps its texture cache the same way). Thread-safe. Read errors
// propagate from Image::Read.
class ImageTextureCache {
  public:
    static std::shared_ptr<const Image> Get(const std::string &filename, ColorEncoding encoding);
    // channels: AlphaOfRGBA for a float texture, which reads an RGBA file's alpha (pbrt-v4).
    static std::shared_ptr<const MIPMap> GetMIPMap(const std::string &filename, ColorEncoding encoding,
                                                   WrapMode wrapMode, MIPMapFilterOptions options,
                                                   ImageChannels channels = ImageChannels::RGB);
    static void Clear();
};

// pbrt-v4's ParseWrapMode: "repeat", "clamp", "black", "octahedralsphere"; empty otherwise.
pstd::optional<WrapMode> ParseWrapMode(const std::string &name);

// ---- The closed sets -------------------------------------------------------------------------

class FloatTexture {
  public:
    using Variant = std::variant<FloatConstantTexture, FloatScaledTexture, FloatMixTexture,
                                 FloatCheckerboardTexture, FloatImageTexture, FloatDotsTexture,
                                 FloatDirectionMixTexture, FloatBilerpTexture, FBmTexture,
                                 WrinkledTexture, WindyTexture>;
    FloatTexture(Float value = 0) : texture(FloatConstantTexture{value}) {}
    template <typename T>
        requires std::is_constructible_v<Variant, T>
    FloatTexture(T texture) : texture(std::move(texture)) {}

    // Defined below the combining textures: clang requires their deduced return types first.
    Float Evaluate(const TextureEvalContext &ctx) const;

  private:
    Variant texture;
};

class SpectrumTexture {
  public:
    using Variant = std::variant<SpectrumConstantTexture, SpectrumScaledTexture, SpectrumMixTexture,
                                 SpectrumCheckerboardTexture, SpectrumImageTexture,
                                 SpectrumDotsTexture, SpectrumDirectionMixTexture,
                                 SpectrumBilerpTexture, MarbleTexture>;
    SpectrumTexture(Spectrum value = Spectrum(0.f)) : texture(SpectrumConstantTexture{std::move(value)}) {}
    template <typename T>
        requires std::is_constructible_v<Variant, T>
    SpectrumTexture(T texture) : texture(std::move(texture)) {}

    SampledSpectrum Evaluate(const TextureEvalContext &ctx, const SampledWavelengths &lambda) const;

  private:
    Variant texture;
};

// ---- Combining textures, now that the handles are complete ----------------------------------

namespace detail {

template <typename Tex>
ScaledTexture<Tex>::ScaledTexture(Tex tex, FloatTexture scale)
    : tex(std::make_shared<const Tex>(std::move(tex))),
      scale(std::make_shared<const FloatTexture>(std::move(scale))) {}

template <typename Tex>
template <typename... Lambda>
auto ScaledTexture<Tex>::Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const {
    Float sc = scale->Evaluate(ctx);
    using Value = decltype(tex->Evaluate(ctx, lambda...));
    if (sc == 0) return Value(0.f);
    return tex->Evaluate(ctx, lambda...) * sc;
}

template <typename Tex>
MixTexture<Tex>::MixTexture(Tex tex1, Tex tex2, FloatTexture amount)
    : tex1(std::make_shared<const Tex>(std::move(tex1))),
      tex2(std::make_shared<const Tex>(std::move(tex2))),
      amount(std::make_shared<const FloatTexture>(std::move(amount))) {}

// Shared by mix and checkerboard: (1 - w) a + w b, evaluating only what has weight.
template <typename Tex, typename... Lambda>
auto Blend(Float w, const Tex &a, const Tex &b, const TextureEvalContext &ctx, const Lambda &...lambda) {
    using Value = decltype(a.Evaluate(ctx, lambda...));
    Value va = (w != 1) ? a.Evaluate(ctx, lambda...) : Value(0.f);
    Value vb = (w != 0) ? b.Evaluate(ctx, lambda...) : Value(0.f);
    return (1 - w) * va + w * vb;
}

template <typename Tex>
template <typename... Lambda>
auto MixTexture<Tex>::Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const {
    return Blend(amount->Evaluate(ctx), *tex1, *tex2, ctx, lambda...);
}

template <typename Tex>
CheckerboardTexture<Tex>::CheckerboardTexture(Mapping mapping, Tex tex1, Tex tex2)
    : mapping(std::move(mapping)),
      tex1(std::make_shared<const Tex>(std::move(tex1))),
      tex2(std::make_shared<const Tex>(std::move(tex2))) {}

template <typename Tex>
template <typename... Lambda>
auto CheckerboardTexture<Tex>::Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const {
    Float w = std::visit([&](const auto &m) { return Checkerboard(m, ctx); }, mapping);
    return Blend(w, *tex1, *tex2, ctx, lambda...);
}

template <typename Tex>
DotsTexture<Tex>::DotsTexture(TextureMapping2D mapping, Tex outside, Tex inside)
    : mapping(std::move(mapping)),
      outside(std::make_shared<const Tex>(std::move(outside))),
      inside(std::make_shared<const Tex>(std::move(inside))) {}

template <typename Tex>
template <typename... Lambda>
auto DotsTexture<Tex>::Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const {
    return InsidePolkaDot(mapping.Map(ctx).st) ? inside->Evaluate(ctx, lambda...)
                                                : outside->Evaluate(ctx, lambda...);
}

template <typename Tex>
DirectionMixTexture<Tex>::DirectionMixTexture(Tex tex1, Tex tex2, Vector3f dir)
    : tex1(std::make_shared<const Tex>(std::move(tex1))),
      tex2(std::make_shared<const Tex>(std::move(tex2))), dir(dir) {}

template <typename Tex>
template <typename... Lambda>
auto DirectionMixTexture<Tex>::Evaluate(const TextureEvalContext &ctx, const Lambda &...lambda) const {
    return Blend(1 - AbsDot(ctx.n, dir), *tex1, *tex2, ctx, lambda...);
}

}  // namespace detail

inline Float FloatTexture::Evaluate(const TextureEvalContext &ctx) const {
    return std::visit([&](const auto &t) { return t.Evaluate(ctx); }, texture);
}

inline SampledSpectrum SpectrumTexture::Evaluate(const TextureEvalContext &ctx,
                                                 const SampledWavelengths &lambda) const {
    return std::visit([&](const auto &t) { return t.Evaluate(ctx, lambda); }, texture);
}

}  // namespace pbrt
