#include "pbrt_ext/integrators/bdpt.h"

#include "pbrt_ext/integrators/bdptvertex.h"
#include "pbrt_ext/integrators/transmittance.h"
#include "pbrt_ext/media/media.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/hash.h"
#include "pbrt_ext/util/rng.h"

#include <filesystem>
#include <optional>
#include <utility>

namespace pbrt {

namespace {

BDPTVertex CameraVertex(Point3f p, Normal3f n, Float time, int medium, SampledSpectrum beta) {
    return {.type = VertexType::Camera, .beta = beta, .p = p, .n = n, .time = time, .medium = medium};
}

BDPTVertex LightVertex(int lightIndex, LightType lightType, Point3f p, Normal3f n, Point2f uv,
                       Float time, int medium, SampledSpectrum beta, Float pdfFwd) {
    return {.type = VertexType::Light, .beta = beta, .p = p, .n = n, .time = time, .medium = medium,
            .lightIndex = lightIndex, .lightType = lightType, .uv = uv, .pdfFwd = pdfFwd};
}

// The infinite lights as seen by a camera ray that escaped (pbrt-v4 places the vertex a unit
// along the ray, facing back).
BDPTVertex EscapedVertex(const Ray &ray, SampledSpectrum beta, Float pdfFwd) {
    Vector3f d = Normalize(ray.d);
    return LightVertex(-1, LightType::Infinite, ray.o + d, Normal3f(-d), Point2f(), ray.time,
                       ray.medium, beta, pdfFwd);
}

// Sets *target to value for the lifetime of the object (pbrt-v4's ScopedAssignment): the MIS
// weight evaluates each strategy's path as if it had been sampled that way.
template <typename T>
class ScopedAssignment {
  public:
    ScopedAssignment() = default;
    ScopedAssignment(T *target, T value) : target(target) {
        if (target) {
            backup = *target;
            *target = value;
        }
    }
    ScopedAssignment(const ScopedAssignment &) = delete;
    ScopedAssignment &operator=(ScopedAssignment &&other) {
        Restore();
        target = std::exchange(other.target, nullptr);
        backup = std::move(other.backup);
        return *this;
    }
    ~ScopedAssignment() { Restore(); }

  private:
    void Restore() {
        if (target)
            *target = backup;
        target = nullptr;
    }
    T *target = nullptr;
    T backup{};
};

// Index of strategy (s, t) among the strategy films.
int BufferIndex(int s, int t) {
    int above = s + t - 2;
    return s + above * (5 + above) / 2;
}

}  // namespace

Float BDPTVertex::PDF(const BDPTIntegrator &integrator, const BDPTVertex *prev,
                      const BDPTVertex &next) const {
    if (type == VertexType::Light)
        return PDFLight(integrator, next);
    Vector3f wn = next.p - p;
    if (LengthSquared(wn) == 0)
        return 0;
    wn = Normalize(wn);
    Vector3f wp;
    if (prev) {
        wp = prev->p - p;
        if (LengthSquared(wp) == 0)
            return 0;
        wp = Normalize(wp);
    }
    Float pdf = 0;
    if (type == VertexType::Camera)
        pdf = integrator.camera.PDF_We(Ray(p, wn, medium, time)).dir;
    else if (type == VertexType::Surface)
        pdf = bsdf->PDF(wp, wn);
    else
        pdf = phase.p(wp, wn);
    return ConvertDensity(pdf, next);
}

Float BDPTVertex::PDFLight(const BDPTIntegrator &integrator, const BDPTVertex &v) const {
    Vector3f w = v.p - p;
    Float invDist2 = 1 / LengthSquared(w);
    w *= std::sqrt(invDist2);
    Float pdf;
    if (IsInfiniteLight()) {
        // The density of the light ray's origin on the scene's bounding disk.
        pdf = 1 / (Pi * Sqr(integrator.sceneRadius));
    } else {
        const Light &light = integrator.scene.lights[EmitterIndex()];
        LightLePDF lp = IsOnSurface() ? light.PDF_Le(p, n, EmitterUV(), w)
                                      : light.PDF_Le(Ray(p, w, medium, time));
        pdf = lp.dir * invDist2;
    }
    if (v.IsOnSurface())
        pdf *= AbsDot(v.n, w);
    return pdf;
}

Float BDPTVertex::PDFLightOrigin(const BDPTIntegrator &integrator, const BDPTVertex &v) const {
    Vector3f w = v.p - p;
    if (LengthSquared(w) == 0)
        return 0;
    w = Normalize(w);
    if (IsInfiniteLight())
        return integrator.InfiniteLightDensity(w);
    int index = EmitterIndex();
    const Light &light = integrator.scene.lights[index];
    LightLePDF lp = IsOnSurface() ? light.PDF_Le(p, n, EmitterUV(), w)
                                  : light.PDF_Le(Ray(p, w, medium, time));
    return lp.pos * integrator.lightSampler.PMF(index);
}

SampledSpectrum BDPTVertex::Le(const Scene &scene, const BDPTVertex &v,
                               const SampledWavelengths &lambda) const {
    if (!IsLight())
        return SampledSpectrum(0.f);
    Vector3f w = v.p - p;
    if (LengthSquared(w) == 0)
        return SampledSpectrum(0.f);
    w = Normalize(w);
    if (IsInfiniteLight()) {
        SampledSpectrum L(0.f);
        for (int index : scene.infiniteLights)
            L += scene.lights[index].Le(Ray(p, -w), lambda);
        return L;
    }
    if (si.areaLightIndex >= 0)
        return scene.lights[si.areaLightIndex].L(si.p, si.n, si.uv, w, lambda);
    return SampledSpectrum(0.f);
}

BDPTIntegrator::BDPTIntegrator(Scene &scene, IntegratorOptions options,
                               std::optional<Float> cameraSampleArea)
    : scene(scene), film(scene.film), options(options), camera(scene.camera, scene.film),
      lightSampler(scene.lights) {
    Point3f center;
    scene.aggregate.WorldBound().BoundingSphere(&center, &sceneRadius);
    Point2i res = film.FullResolution();
    cropScale = Float(res.x) * Float(res.y) /
                cameraSampleArea.value_or(Float(film.PixelBounds().Area()));
    film.EnableSplats();
    if (!options.visualizeStrategies && !options.visualizeWeights)
        return;
    strategyFilms.resize(BufferIndex(0, options.maxDepth + 3));
    std::filesystem::path folder = std::filesystem::path(film.GetFilename()).parent_path();
    for (int depth = 0; depth <= options.maxDepth; ++depth)
        for (int s = 0; s <= depth + 2; ++s) {
            int t = depth + 2 - s;
            if (t == 0 || (s == 1 && t == 1))
                continue;
            char name[64];
            std::snprintf(name, sizeof(name), "bdpt_d%02d_s%02d_t%02d.exr", depth, s, t);
            auto strategy = std::make_unique<RGBFilm>(res, film.PixelBounds(), Filter(BoxFilter()),
                                                      (folder / name).string(), Infinity,
                                                      film.Sensor(), &film.ColorSpace());
            strategy->EnableSplats(false);  // diagnostics: one set of sums each, not per thread
            strategyFilms[BufferIndex(s, t)] = std::move(strategy);
        }
}

RGBFilm *BDPTIntegrator::StrategyFilm(int s, int t) const {
    return strategyFilms.empty() ? nullptr : strategyFilms[BufferIndex(s, t)].get();
}

void BDPTIntegrator::WriteStrategyImages(Float splatScale) const {
    for (const std::unique_ptr<RGBFilm> &strategy : strategyFilms)
        if (strategy) {
            strategy->SetSplatScale(splatScale);
            strategy->WriteImage(ImageMetadata());
        }
}

Float BDPTIntegrator::InfiniteLightDensity(Vector3f w) const {
    Float pdf = 0;
    for (int index : scene.infiniteLights)
        pdf += scene.lights[index].PDF_Li(LightSampleContext(), -w) * lightSampler.PMF(index);
    return pdf;
}

SampledSpectrum BDPTIntegrator::Li(RayDifferential ray, Point2f pFilm, SampledWavelengths &lambda,
                                   Sampler &sampler, RayCounts &rays) const {
    // Per thread, reused: a vertex holds a whole interaction and BSDF.
    thread_local std::vector<BDPTVertex> cameraVertices, lightVertices;
    cameraVertices.resize(options.maxDepth + 2);
    lightVertices.resize(options.maxDepth + 1);
    int nCamera = GenerateCameraSubpath(ray, lambda, sampler, rays, cameraVertices.data(),
                                        options.maxDepth + 2);
    int nLight = GenerateLightSubpath(lambda, sampler, cameraVertices[0].time, rays,
                                      lightVertices.data(), options.maxDepth + 1);
    SampledSpectrum L(0.f);
    for (int t = 1; t <= nCamera; ++t)
        for (int s = 0; s <= nLight; ++s) {
            int depth = t + s - 2;
            if ((s == 1 && t == 1) || depth < 0 || depth > options.maxDepth)
                continue;
            pstd::optional<Point2f> pFilmNew;
            Float misWeight = 0;
            SampledSpectrum Lpath = ConnectBDPT(lambda, lightVertices.data(), cameraVertices.data(),
                                                s, t, sampler, rays, &pFilmNew, &misWeight);
            if (!Lpath)
                continue;
            if (RGBFilm *strategy = StrategyFilm(s, t)) {
                SampledSpectrum value = options.visualizeWeights ? Lpath : Lpath / misWeight;
                strategy->AddSplat(pFilmNew ? *pFilmNew : pFilm, value, lambda);
            }
            if (t != 1)
                L += Lpath;
            else
                film.AddSplat(*pFilmNew, Lpath, lambda);
        }
    return L;
}

int BDPTIntegrator::GenerateCameraSubpath(const RayDifferential &ray, SampledWavelengths &lambda,
                                          Sampler &sampler, RayCounts &rays, BDPTVertex *path,
                                          int maxVertices) const {
    if (maxVertices == 0)
        return 0;
    path[0] = CameraVertex(ray.o, Normal3f(0, 0, 0), ray.time, ray.medium, SampledSpectrum(1.f));
    Float pdfDir = camera.PDF_We(ray).dir;
    return RandomWalk(lambda, ray, sampler, SampledSpectrum(1.f), pdfDir, maxVertices - 1,
                      TransportMode::Radiance, rays, path + 1) +
           1;
}

int BDPTIntegrator::GenerateLightSubpath(SampledWavelengths &lambda, Sampler &sampler, Float time,
                                         RayCounts &rays, BDPTVertex *path, int maxVertices) const {
    if (maxVertices == 0)
        return 0;
    pstd::optional<SampledLight> sampled = lightSampler.Sample(sampler.Get1D());
    if (!sampled)
        return 0;
    const Light &light = scene.lights[sampled->lightIndex];
    Point2f ul0 = sampler.Get2D(), ul1 = sampler.Get2D();
    pstd::optional<LightLeSample> les = light.SampleLe(ul0, ul1, lambda, time);
    if (!les || les->pdfPos == 0 || les->pdfDir == 0 || !les->L)
        return 0;
    RayDifferential ray(les->ray);
    const MediumInterface &mi = scene.lightMediumInterfaces[sampled->lightIndex];
    ray.medium = les->OnSurface() && Dot(ray.d, les->n) < 0 ? mi.inside : mi.outside;
    Float p_l = sampled->p * les->pdfPos;
    path[0] = LightVertex(sampled->lightIndex, light.Type(), ray.o, les->n, les->uv, time,
                          ray.medium, les->L, p_l);
    SampledSpectrum beta = les->L * les->AbsCosTheta(ray.d) / (p_l * les->pdfDir);
    int nVertices = RandomWalk(lambda, ray, sampler, beta, les->pdfDir, maxVertices - 1,
                               TransportMode::Importance, rays, path + 1);
    // An infinite light's subpath starts at a direction, then a point on the scene's disk.
    if (path[0].IsInfiniteLight()) {
        if (nVertices > 0) {
            path[1].pdfFwd = les->pdfPos;
            if (path[1].IsOnSurface())
                path[1].pdfFwd *= AbsDot(ray.d, path[1].n);
        }
        path[0].pdfFwd = InfiniteLightDensity(ray.d);
    }
    return nVertices + 1;
}

// A subpath's random walk in progress: its ray and throughput, and path[bounces], the vertex it
// will make next (path[bounces - 1] made the ray: the subpath's origin when bounces is 0).
struct BDPTIntegrator::Walk {
    RayDifferential ray;
    SampledSpectrum beta;
    TransportMode mode;
    int maxDepth;
    BDPTVertex *path;
    int bounces;
    bool anyNonSpecularBounces;
    // The density of the ray's direction from path[bounces - 1]. A layered BSDF's sample gives
    // only a proportional one, and its PDF() is a random walk: that is evaluated once the
    // direction has reached a vertex to store it in (none where a light subpath escapes, or a
    // camera subpath escapes a scene without infinite lights).
    Float pdfFwd;
    std::optional<Vector3f> wiPdfPending;

    BDPTVertex &Next() { return path[bounces]; }
    BDPTVertex &Last() { return path[bounces - 1]; }
    Float ForwardDensity() {
        if (wiPdfPending)
            pdfFwd = Last().bsdf->PDF(Last().si.wo, *std::exchange(wiPdfPending, std::nullopt), mode);
        return pdfFwd;
    }
};

int BDPTIntegrator::RandomWalk(SampledWavelengths &lambda, RayDifferential ray, Sampler &sampler,
                               SampledSpectrum beta, Float pdf, int maxDepth, TransportMode mode,
                               RayCounts &rays, BDPTVertex *path) const {
    if (maxDepth == 0)
        return 0;
    Walk walk{.ray = ray, .beta = beta, .mode = mode, .maxDepth = maxDepth, .path = path,
              .bounces = 0, .anyNonSpecularBounces = false, .pdfFwd = pdf, .wiPdfPending = {}};
    while (walk.beta) {
        ++rays.closest;
        pstd::optional<ShapeIntersection> hit = scene.Intersect(walk.ray);
        if (walk.ray.medium >= 0) {
            MediumStep step = TrackThroughMedium(walk, hit ? hit->tHit : Infinity, lambda, sampler);
            if (step == MediumStep::Ended)
                return walk.bounces;
            if (step == MediumStep::Scattered)
                continue;
        }
        if (!hit) {
            // Camera subpaths end at the infinite lights they escape to, if there are any.
            if (mode == TransportMode::Radiance && !scene.infiniteLights.empty()) {
                walk.Next() = EscapedVertex(walk.ray, walk.beta, walk.ForwardDensity());
                ++walk.bounces;
            }
            break;
        }
        SurfaceInteraction &si = hit->intr;
        scene.ComputeDifferentials(si, walk.ray);
        std::optional<BSDF> bsdf = scene.GetBSDF(si, lambda);
        if (!bsdf) {
            walk.ray = RayDifferential(si.SpawnRay(walk.ray.d));  // an interface between media
            continue;
        }
        if (!ScatterAtSurface(walk, si, *bsdf, sampler))
            break;
    }
    return walk.bounces;
}

BDPTIntegrator::MediumStep BDPTIntegrator::TrackThroughMedium(Walk &walk, Float tMax,
                                                              const SampledWavelengths &lambda,
                                                              Sampler &sampler) const {
    // Absorption ends the subpath, a real collision makes a medium vertex, null collisions
    // pass on.
    MediumStep step = MediumStep::PassedThrough;
    const Ray &ray = walk.ray;
    RNG rng(Hash(ray.o, tMax), Hash(ray.d));
    SampledSpectrum T_majEnd = scene.media[ray.medium].SampleT_maj(
        ray, tMax, sampler.Get1D(), rng, lambda,
        [&](Point3f p, const MediumProperties &mp, SampledSpectrum sigma_maj, SampledSpectrum T_maj) {
            Float pAbsorb = mp.sigma_a[0] / sigma_maj[0];
            Float pScatter = mp.sigma_s[0] / sigma_maj[0];
            Float pNull = std::max<Float>(0, 1 - pAbsorb - pScatter);
            Float um = sampler.Get1D() * (pAbsorb + pScatter + pNull);
            if (um < pAbsorb) {
                step = MediumStep::Ended;
                return false;
            }
            if (um < pAbsorb + pScatter) {
                walk.beta *= T_maj * mp.sigma_s / (T_maj[0] * mp.sigma_s[0]);
                BDPTVertex &vertex = walk.Next(), &prev = walk.Last();
                vertex = BDPTVertex();
                vertex.type = VertexType::Medium;
                vertex.p = p;
                vertex.wo = -Normalize(ray.d);
                vertex.phase = mp.phase;
                vertex.medium = ray.medium;
                vertex.time = ray.time;
                vertex.beta = walk.beta;
                vertex.pdfFwd = prev.ConvertDensity(walk.ForwardDensity(), vertex);
                // The subpath ends at this vertex unless it samples a direction on.
                step = MediumStep::Ended;
                if (++walk.bounces >= walk.maxDepth)
                    return false;
                std::optional<PhaseFunctionSample> ps = vertex.phase.Sample_p(vertex.wo, sampler.Get2D());
                if (!ps || ps->pdf == 0)
                    return false;
                walk.pdfFwd = ps->pdf;
                walk.beta *= ps->p / ps->pdf;
                walk.ray = RayDifferential(Ray(p, ps->wi, ray.medium, ray.time));
                walk.anyNonSpecularBounces = true;
                prev.pdfRev = vertex.ConvertDensity(ps->pdf, prev);
                step = MediumStep::Scattered;
                return false;
            }
            SampledSpectrum sigma_n = ClampZero(sigma_maj - mp.sigma_a - mp.sigma_s);
            Float pdfNull = T_maj[0] * sigma_n[0];
            walk.beta = pdfNull == 0 ? SampledSpectrum(0.f) : walk.beta * T_maj * sigma_n / pdfNull;
            return bool(walk.beta);
        },
        MediumQuery::NoEmission);
    if (step == MediumStep::PassedThrough)
        walk.beta *= T_majEnd / T_majEnd[0];
    return step;
}

bool BDPTIntegrator::ScatterAtSurface(Walk &walk, const SurfaceInteraction &si, BSDF bsdf,
                                      Sampler &sampler) const {
    if (options.regularize && walk.anyNonSpecularBounces)
        bsdf.Regularize();
    BDPTVertex &vertex = walk.Next(), &prev = walk.Last();
    vertex = BDPTVertex();
    vertex.type = VertexType::Surface;
    vertex.si = si;
    vertex.bsdf = bsdf;
    vertex.p = si.p;
    vertex.n = si.n;
    vertex.time = si.time;
    vertex.beta = walk.beta;
    vertex.pdfFwd = prev.ConvertDensity(walk.ForwardDensity(), vertex);
    if (++walk.bounces >= walk.maxDepth)
        return false;
    Vector3f wo = si.wo;
    Float u = sampler.Get1D();
    pstd::optional<BSDFSample> bs = bsdf.Sample_f(wo, u, sampler.Get2D(), walk.mode);
    if (!bs)
        return false;
    walk.pdfFwd = bs->pdf;
    if (bs->pdfIsProportional && !bs->IsSpecular())
        walk.wiPdfPending = bs->wi;
    walk.anyNonSpecularBounces |= !bs->IsSpecular();
    walk.beta *= bs->f * AbsDot(bs->wi, Vector3f(si.shading.n)) / bs->pdf;
    walk.ray = si.SpawnRay(walk.ray, bs->wi, bs->flags, bs->eta);
    TransportMode reverse = walk.mode == TransportMode::Radiance ? TransportMode::Importance
                                                                 : TransportMode::Radiance;
    Float pdfRev = prev.PdfRevIsRead() ? bsdf.PDF(bs->wi, wo, reverse) : 0;
    if (bs->IsSpecular()) {
        vertex.delta = true;
        pdfRev = walk.pdfFwd = 0;
    }
    prev.pdfRev = vertex.ConvertDensity(pdfRev, prev);
    return true;
}

// Strategies s = 1 and t = 1 sample the endpoint they connect to; it is a local vertex, built
// only by them (a whole BDPTVertex is 464 bytes: an optional one on every call zeroed them for
// every strategy).
SampledSpectrum BDPTIntegrator::ConnectBDPT(SampledWavelengths &lambda, BDPTVertex *lightVertices,
                                            BDPTVertex *cameraVertices, int s, int t, Sampler &sampler,
                                            RayCounts &rays, pstd::optional<Point2f> *pRaster,
                                            Float *misWeight) const {
    // An escaped camera ray has nothing to connect to.
    if (t > 1 && s != 0 && cameraVertices[t - 1].type == VertexType::Light)
        return SampledSpectrum(0.f);
    if (s != 0 && t == 1)
        return ConnectToCamera(lambda, lightVertices, cameraVertices, s, sampler, rays, pRaster, misWeight);
    if (s == 1)
        return ConnectToLight(lambda, lightVertices, cameraVertices, t, sampler, rays, misWeight);
    SampledSpectrum L(0.f);
    if (s == 0) {
        // The camera subpath alone, ending on an emitter.
        const BDPTVertex &pt = cameraVertices[t - 1];
        if (pt.IsLight())
            L = pt.Le(scene, cameraVertices[t - 2], lambda) * pt.beta;
    } else {
        // Both subpaths, joined by a segment.
        const BDPTVertex &qs = lightVertices[s - 1], &pt = cameraVertices[t - 1];
        if (!qs.IsConnectible() || !pt.IsConnectible())
            return SampledSpectrum(0.f);
        L = qs.beta * qs.f(pt, TransportMode::Importance) * pt.f(qs, TransportMode::Radiance) * pt.beta;
        if (L) {
            Vector3f d = qs.p - pt.p;
            Float g = 1 / LengthSquared(d);
            d *= std::sqrt(g);
            if (qs.IsOnSurface())
                g *= AbsDot(Vector3f(qs.ns()), d);
            if (pt.IsOnSurface())
                g *= AbsDot(Vector3f(pt.ns()), d);
            L *= g * Transmittance(scene, qs.SpawnRayTo(pt.p), pt.p, lambda, rays);
        }
    }
    return WeightedByMIS(L, lightVertices, cameraVertices, nullptr, s, t, misWeight);
}

// t = 1: a lens point for the light subpath.
SampledSpectrum BDPTIntegrator::ConnectToCamera(SampledWavelengths &lambda, BDPTVertex *lightVertices,
                                                BDPTVertex *cameraVertices, int s, Sampler &sampler,
                                                RayCounts &rays, pstd::optional<Point2f> *pRaster,
                                                Float *misWeight) const {
    const BDPTVertex &qs = lightVertices[s - 1];
    if (!qs.IsConnectible())
        return SampledSpectrum(0.f);
    pstd::optional<CameraWiSample> cs = camera.SampleWi(qs.p, qs.time, sampler.Get2D());
    if (!cs)
        return SampledSpectrum(0.f);
    *pRaster = cs->pRaster;
    film.PrefetchSplat(cs->pRaster);
    BDPTVertex sampled = CameraVertex(cs->pLens, cs->nLens, qs.time, scene.cameraMedium, cs->Wi / cs->pdf);
    SampledSpectrum L = qs.beta * qs.f(sampled, TransportMode::Importance) * sampled.beta;
    if (qs.IsOnSurface())
        L *= AbsDot(cs->wi, Vector3f(qs.ns()));
    if (L)
        L *= cropScale * Transmittance(scene, qs.SpawnRayTo(cs->pLens), cs->pLens, lambda, rays);
    return WeightedByMIS(L, lightVertices, cameraVertices, &sampled, s, 1, misWeight);
}

// s = 1: a light point for the camera subpath (next-event estimation).
SampledSpectrum BDPTIntegrator::ConnectToLight(SampledWavelengths &lambda, BDPTVertex *lightVertices,
                                               BDPTVertex *cameraVertices, int t, Sampler &sampler,
                                               RayCounts &rays, Float *misWeight) const {
    const BDPTVertex &pt = cameraVertices[t - 1];
    if (!pt.IsConnectible())
        return SampledSpectrum(0.f);
    pstd::optional<SampledLight> chosen = lightSampler.Sample(sampler.Get1D());
    Point2f u = sampler.Get2D();
    if (!chosen)
        return SampledSpectrum(0.f);
    const Light &light = scene.lights[chosen->lightIndex];
    // From the surface point itself, as the path tracer samples lights. (pbrt-v4 moves it off
    // the surface to the side the BSDF scatters to; on a surface that emits too, that point
    // then sees its own emitter as a hemisphere of light: 2 % too much of the light two
    // bounces deep in BDPTStrategies' scene, where the lamp's shade reflects.)
    LightSampleContext ctx = pt.type == VertexType::Surface
                                 ? LightSampleContext(pt.si)
                                 : LightSampleContext(pt.p, Normal3f(0, 0, 0), Normal3f(0, 0, 0));
    pstd::optional<LightLiSample> ls = light.SampleLi(ctx, u, lambda);
    if (!ls || !ls->L || !(ls->pdf > 0))
        return SampledSpectrum(0.f);
    BDPTVertex sampled = LightVertex(chosen->lightIndex, light.Type(), ls->pLight, ls->nLight, ls->uvLight,
                                     pt.time, pt.medium, ls->L / (ls->pdf * chosen->p), 0);
    SampledSpectrum L = pt.beta * pt.f(sampled, TransportMode::Radiance) * sampled.beta;
    if (pt.IsOnSurface())
        L *= AbsDot(ls->wi, Vector3f(pt.ns()));
    if (L)
        L *= Transmittance(scene, pt.SpawnRayTo(ls->pLight), ls->pLight, lambda, rays);
    // Only the MIS weight reads it, and only of a contribution.
    if (L)
        sampled.pdfFwd = sampled.PDFLightOrigin(*this, pt);
    return WeightedByMIS(L, lightVertices, cameraVertices, &sampled, 1, t, misWeight);
}

SampledSpectrum BDPTIntegrator::WeightedByMIS(SampledSpectrum L, BDPTVertex *lightVertices,
                                              BDPTVertex *cameraVertices, BDPTVertex *sampled, int s,
                                              int t, Float *misWeight) const {
    *misWeight = L ? MISWeight(lightVertices, cameraVertices, sampled, s, t) : 0;
    return L * *misWeight;
}

Float BDPTIntegrator::MISWeight(BDPTVertex *lightVertices, BDPTVertex *cameraVertices,
                                BDPTVertex *sampled, int s, int t) const {
    if (s + t == 2)
        return 1;
    // Densities of 0 are specular bounces' or delta lights': their ratios count as 1, and the
    // strategies that would have to sample them are left out below.
    auto remap0 = [](Float f) -> Float { return f != 0 ? f : 1; };
    // The path as this strategy made it: with the endpoint it sampled in place of the subpath's.
    auto light = [&](int i) -> BDPTVertex & { return s == 1 && i == 0 ? *sampled : lightVertices[i]; };
    auto camera = [&](int i) -> BDPTVertex & { return t == 1 && i == 0 ? *sampled : cameraVertices[i]; };
    BDPTVertex *qs = s > 0 ? &light(s - 1) : nullptr, *pt = t > 0 ? &camera(t - 1) : nullptr,
               *qsMinus = s > 1 ? &light(s - 2) : nullptr, *ptMinus = t > 1 ? &camera(t - 2) : nullptr;

    // Connection vertices that are not degenerate, and the reverse densities across the
    // connection (those the ratios below read).
    ScopedAssignment<bool> a2, a3;
    if (pt)
        a2 = {&pt->delta, false};
    if (qs)
        a3 = {&qs->delta, false};
    ScopedAssignment<Float> a4;
    if (pt && pt->PdfRevIsRead())
        a4 = {&pt->pdfRev, s > 0 ? qs->PDF(*this, qsMinus, *pt) : pt->PDFLightOrigin(*this, *ptMinus)};
    ScopedAssignment<Float> a5;
    if (ptMinus && ptMinus->PdfRevIsRead())
        a5 = {&ptMinus->pdfRev, s > 0 ? pt->PDF(*this, qs, *ptMinus) : pt->PDFLight(*this, *ptMinus)};
    ScopedAssignment<Float> a6;
    if (qs && qs->PdfRevIsRead())
        a6 = {&qs->pdfRev, pt->PDF(*this, ptMinus, *qs)};
    ScopedAssignment<Float> a7;
    if (qsMinus && qsMinus->PdfRevIsRead())
        a7 = {&qsMinus->pdfRev, qs->PDF(*this, pt, *qsMinus)};

    // The other strategies for the same path, as ratios of their densities to this one's.
    Float sumRi = 0, ri = 1;
    for (int i = t - 1; i > 0; --i) {
        ri *= remap0(camera(i).pdfRev) / remap0(camera(i).pdfFwd);
        if (i == 1)
            ri /= cropScale;  // the t = 1 strategy's contributions are scaled up by it
        if (!camera(i).delta && !camera(i - 1).delta)
            sumRi += ri;
    }
    ri = 1;
    for (int i = s - 1; i >= 0; --i) {
        ri *= remap0(light(i).pdfRev) / remap0(light(i).pdfFwd);
        bool deltaLightVertex = i > 0 ? light(i - 1).delta : light(0).IsDeltaLight();
        if (!light(i).delta && !deltaLightVertex)
            sumRi += ri;
    }
    // Light paths spread over the whole film, so with a crop window the t = 1 strategy samples
    // a pixel cropScale times more rarely than the others: its weight is its density over
    // cropScale against theirs. (pbrt-v4 divides here too, and its weights then sum to more
    // than 1 on every path that t = 1 can make: bdptmis_test.)
    if (t == 1)
        sumRi *= cropScale;
    return 1 / (1 + sumRi);
}

}  // namespace pbrt
