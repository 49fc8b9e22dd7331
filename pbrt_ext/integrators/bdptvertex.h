// A vertex of bdpt's camera and light subpaths (pbrt-v4's Vertex, bdpt.h's BDPTVertex): what
// the connections and MIS weights of bdpt.cpp read of it. Private to bdpt.cpp.
#pragma once

#include "pbrt_ext/interaction.h"
#include "pbrt_ext/lights/lightsample.h"
#include "pbrt_ext/materials/bsdf.h"
#include "pbrt_ext/media/media.h"
#include "pbrt_ext/util/spectrum.h"
#include "pbrt_ext/util/vecmath.h"

#include <cmath>
#include <optional>

namespace pbrt {

class BDPTIntegrator;
class Scene;

enum class VertexType { Camera, Light, Surface, Medium };

// A vertex of a camera or light subpath (pbrt-v4's Vertex): where it is, the throughput beta of
// the subpath up to it, and the densities of reaching it from its predecessor (pdfFwd) and from
// its successor (pdfRev), per unit area (per unit solid angle for infinite lights).
struct BDPTVertex {
    VertexType type = VertexType::Camera;
    SampledSpectrum beta{0.f};
    Point3f p{};
    Normal3f n{};  // geometric normal; zero off surfaces
    Float time = 0;
    int medium = -1;  // the medium a camera, light or medium vertex is in
    // Surface vertices.
    SurfaceInteraction si{};
    std::optional<BSDF> bsdf{};
    // Medium vertices.
    Vector3f wo{};
    HGPhaseFunction phase{};
    // Light vertices: the light (-1: the infinite lights an escaped camera ray sees), its type,
    // and the surface parameters of a point on an area light.
    int lightIndex = -1;
    LightType lightType = LightType::Infinite;
    Point2f uv{};
    bool delta = false;  // scattered by a specular lobe
    Float pdfFwd = 0, pdfRev = 0;

    Normal3f ns() const { return type == VertexType::Surface ? si.shading.n : n; }
    bool IsOnSurface() const { return n != Normal3f(0, 0, 0); }
    bool IsConnectible() const {
        switch (type) {
        case VertexType::Light:
            return lightType != LightType::DeltaDirection;
        case VertexType::Surface:
            return IsNonSpecular(bsdf->Flags());
        default:
            return true;
        }
    }
    bool IsLight() const {
        return type == VertexType::Light || (type == VertexType::Surface && si.areaLightIndex >= 0);
    }
    bool IsDeltaLight() const {
        return type == VertexType::Light && lightIndex >= 0 && pbrt::IsDeltaLight(lightType);
    }
    // Whether a MIS weight ever reads pdfRev here. Two kinds of subpath origin it never reads:
    // the camera's, since no strategy samples the lens from the scene (light subpaths do not
    // hit it), and a delta light's, since no camera subpath can hit one. Their reverse
    // densities are not computed: at a layered BSDF each is a random walk of its own.
    bool PdfRevIsRead() const { return type != VertexType::Camera && !IsDeltaLight(); }
    bool IsInfiniteLight() const {
        return type == VertexType::Light &&
               (lightType == LightType::Infinite || lightType == LightType::DeltaDirection);
    }
    // The emitter this vertex is on: a light vertex's, or the area light of a surface.
    int EmitterIndex() const { return type == VertexType::Light ? lightIndex : si.areaLightIndex; }
    Point2f EmitterUV() const { return type == VertexType::Light ? uv : si.uv; }

    // The BSDF or phase function toward next.
    SampledSpectrum f(const BDPTVertex &next, TransportMode mode) const {
        Vector3f wi = next.p - p;
        if (LengthSquared(wi) == 0)
            return SampledSpectrum(0.f);
        wi = Normalize(wi);
        if (type == VertexType::Surface)
            return bsdf->f(si.wo, wi, mode);
        return SampledSpectrum(phase.p(wo, wi));
    }

    // pdf per unit solid angle at this vertex, converted to a density at next.
    Float ConvertDensity(Float pdf, const BDPTVertex &next) const {
        if (next.IsInfiniteLight())
            return pdf;
        Vector3f w = next.p - p;
        if (LengthSquared(w) == 0)
            return 0;
        Float invDist2 = 1 / LengthSquared(w);
        if (next.IsOnSurface())
            pdf *= AbsDot(next.n, w * std::sqrt(invDist2));
        return pdf * invDist2;
    }

    // A ray from this vertex to target, with d = target - o.
    Ray SpawnRayTo(Point3f target) const {
        if (type == VertexType::Surface)
            return si.SpawnRayTo(target);
        return Ray(p, target - p, medium, time);
    }

    // The density of sampling next from this vertex, whose predecessor on its subpath is prev.
    Float PDF(const BDPTIntegrator &integrator, const BDPTVertex *prev, const BDPTVertex &next) const;
    // The density of a light vertex emitting toward v, per unit area at v.
    Float PDFLight(const BDPTIntegrator &integrator, const BDPTVertex &v) const;
    // The density of a light subpath starting at this light vertex (toward v).
    Float PDFLightOrigin(const BDPTIntegrator &integrator, const BDPTVertex &v) const;
    // Emitted radiance toward v.
    SampledSpectrum Le(const Scene &scene, const BDPTVertex &v, const SampledWavelengths &lambda) const;
};

}  // namespace pbrt
