// Texture mappings (pbrt-v4's TextureMapping2D and TextureMapping3D): where on a texture a
// shading point falls, and how far that moves across the pixel's footprint.
//
// The 2D mappings are pbrt-v4's "uv", "spherical", "cylindrical" and "planar"; the 3D one
// transforms the point into texture space. Texture space is the CTM at the Texture directive
// (worldFromTexture). One correction: pbrt-v4's spherical mapping gives s = theta / pi but the
// derivatives of phi / 2pi as ds/dx (and the other way round for t); here each coordinate has its
// own derivatives, which only changes how wide a filtered lookup is.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/util/transform.h"

#include <type_traits>
#include <variant>

namespace pbrt {

// What a texture may read at a shading point.
struct TextureEvalContext {
    TextureEvalContext() = default;
    explicit TextureEvalContext(const SurfaceInteraction &si)
        : p(si.p), dpdx(si.dpdx), dpdy(si.dpdy), n(si.n), uv(si.uv), dudx(si.dudx),
          dudy(si.dudy), dvdx(si.dvdx), dvdy(si.dvdy) {}
    Point3f p;
    Vector3f dpdx, dpdy;  // the pixel's footprint (ray differentials), zero where unknown
    Normal3f n;
    Point2f uv;
    Float dudx = 0, dudy = 0, dvdx = 0, dvdy = 0;
};

// Texture coordinates and their derivatives along the pixel's x and y.
struct TexCoord2D {
    Point2f st;
    Float dsdx = 0, dsdy = 0, dtdx = 0, dtdy = 0;
};

// A point in texture space and its derivatives along the pixel's x and y.
struct TexCoord3D {
    Point3f p;
    Vector3f dpdx, dpdy;
};

// (s, t) = (su u + du, sv v + dv).
struct UVMapping {
    Float su = 1, sv = 1, du = 0, dv = 0;
    TexCoord2D Map(const TextureEvalContext &ctx) const {
        return TexCoord2D{Point2f(su * ctx.uv[0] + du, sv * ctx.uv[1] + dv), su * ctx.dudx,
                          su * ctx.dudy, sv * ctx.dvdx, sv * ctx.dvdy};
    }
};

// (s, t) = (theta / pi, phi / 2pi) of the direction from texture space's origin.
struct SphericalMapping {
    Transform worldFromTexture;
    TexCoord2D Map(const TextureEvalContext &ctx) const;
};

// (s, t) = ((pi + atan2(y, x)) / 2pi, z) in texture space.
struct CylindricalMapping {
    Transform worldFromTexture;
    TexCoord2D Map(const TextureEvalContext &ctx) const;
};

// (s, t) = (ds + p . vs, dt + p . vt) in texture space.
struct PlanarMapping {
    Transform worldFromTexture;
    Vector3f vs{1, 0, 0}, vt{0, 1, 0};
    Float ds = 0, dt = 0;
    TexCoord2D Map(const TextureEvalContext &ctx) const;
};

class TextureMapping2D {
  public:
    using Variant = std::variant<UVMapping, SphericalMapping, CylindricalMapping, PlanarMapping>;
    TextureMapping2D() = default;
    template <typename M>
        requires std::is_constructible_v<Variant, M>
    TextureMapping2D(M mapping) : mapping(std::move(mapping)) {}
    TexCoord2D Map(const TextureEvalContext &ctx) const {
        return std::visit([&](const auto &m) { return m.Map(ctx); }, mapping);
    }

  private:
    Variant mapping;
};

// pbrt-v4's PointTransformMapping: the point and its footprint in texture space.
struct TextureMapping3D {
    Transform worldFromTexture;
    TexCoord3D Map(const TextureEvalContext &ctx) const {
        return TexCoord3D{worldFromTexture.ApplyInverse(ctx.p), worldFromTexture.ApplyInverse(ctx.dpdx),
                          worldFromTexture.ApplyInverse(ctx.dpdy)};
    }
};

}  // namespace pbrt
