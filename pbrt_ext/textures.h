// Textures: what a material's parameters vary with over a surface (pbrt-v4's src/pbrt/textures.h).
// The closed sets of float and spectrum textures are listed here; the scene-file issue adds image maps
// and procedural ones. A constant parameter is evaluated without any lookup.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/util/spectrum.h"

#include <type_traits>
#include <variant>

namespace pbrt {

// What a texture may read at a shading point.
struct TextureEvalContext {
    TextureEvalContext() = default;
    explicit TextureEvalContext(const SurfaceInteraction &si) : p(si.p), n(si.n), uv(si.uv) {}
    Point3f p;
    Normal3f n;
    Point2f uv;
};

struct FloatConstantTexture {
    Float value;
    Float Evaluate(const TextureEvalContext &) const { return value; }
};

struct SpectrumConstantTexture {
    SampledSpectrum value;
    SampledSpectrum Evaluate(const TextureEvalContext &) const { return value; }
};

class FloatTexture {
  public:
    using Variant = std::variant<FloatConstantTexture>;
    FloatTexture(Float value = 0) : texture(FloatConstantTexture{value}) {}
    template <typename T>
        requires std::is_constructible_v<Variant, T>
    FloatTexture(T texture) : texture(std::move(texture)) {}

    Float Evaluate(const TextureEvalContext &ctx) const {
        return std::visit([&](const auto &t) { return t.Evaluate(ctx); }, texture);
    }

  private:
    Variant texture;
};

class SpectrumTexture {
  public:
    using Variant = std::variant<SpectrumConstantTexture>;
    SpectrumTexture(SampledSpectrum value = SampledSpectrum(0.f))
        : texture(SpectrumConstantTexture{value}) {}
    template <typename T>
        requires std::is_constructible_v<Variant, T>
    SpectrumTexture(T texture) : texture(std::move(texture)) {}

    SampledSpectrum Evaluate(const TextureEvalContext &ctx) const {
        return std::visit([&](const auto &t) { return t.Evaluate(ctx); }, texture);
    }

  private:
    Variant texture;
};

}  // namespace pbrt
