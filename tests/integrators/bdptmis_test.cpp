// bdpt's MIS weights, path by path: every strategy (s, t) that can make a path gives it a weight,
// and those weights must add up to one for each path, or the image is biased where they do not.
// The paths are random ones that bdpt's own walks trace; each is split in every way, its
// vertices' densities computed afresh for each split, and BDPTIntegrator::MISWeight asked for the
// weight of each. The walks' own densities are checked against the same fresh ones.
#include "tests/support/scenefolder.h"

#include "pbrt_ext/integrators/bdpt.h"
#include "pbrt_ext/integrators/bdptvertex.h"
#include "pbrt_ext/scene.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <map>
#include <string>
#include <vector>

namespace pbrt {

// The integrator's subpaths and weights, which are private to it.
struct BDPTTestAccess {
    static int CameraSubpath(const BDPTIntegrator &bdpt, const RayDifferential &ray,
                             SampledWavelengths &lambda, Sampler &sampler, BDPTVertex *path) {
        RayCounts rays;
        return bdpt.GenerateCameraSubpath(ray, lambda, sampler, rays, path, bdpt.options.maxDepth + 2);
    }
    static int LightSubpath(const BDPTIntegrator &bdpt, SampledWavelengths &lambda,
                            Sampler &sampler, Float time, BDPTVertex *path) {
        RayCounts rays;
        return bdpt.GenerateLightSubpath(lambda, sampler, time, rays, path, bdpt.options.maxDepth + 1);
    }
    static Float MISWeight(const BDPTIntegrator &bdpt, BDPTVertex *light, BDPTVertex *camera,
                           BDPTVertex *sampled, int s, int t) {
        return bdpt.MISWeight(light, camera, sampled, s, t);
    }
    static int MaxDepth(const BDPTIntegrator &bdpt) { return bdpt.options.maxDepth; }
};

namespace {

struct Variant {
    const char *name;
    bool crop;  // a crop window: the light-tracing strategy t = 1 then reaches fewer pixels
    bool fog;   // a homogeneous medium around everything: medium vertices
};

// A floor under an area light, a spot light and a sky, with a sphere of each kind of surface
// that bdpt treats differently: diffuse, glossy, specular reflection and refraction, rough
// refraction and fabric.
std::string SceneText(const Variant &v) {
    std::string text;
    if (v.fog)
        text += "MakeNamedMedium \"fog\" \"string type\" \"homogeneous\" "
                "\"rgb sigma_a\" [0.02 0.03 0.04] \"rgb sigma_s\" [0.12 0.1 0.08] \"float g\" 0.3\n"
                "MediumInterface \"\" \"fog\"\n";
    text += "LookAt 0 2.5 -6  0 0.6 0  0 1 0\n"
            "Camera \"perspective\" \"float fov\" 45\n"
            "Film \"rgb\" \"integer xresolution\" 64 \"integer yresolution\" 48 "
            "\"string filename\" \"mis.exr\"";
    if (v.crop)
        text += " \"float cropwindow\" [0.25 0.75 0.2 0.6]";
    text += "\nSampler \"independent\" \"integer pixelsamples\" 1\n"
            "Integrator \"bdpt\" \"integer maxdepth\" 7\n"
            "WorldBegin\n"
            "LightSource \"infinite\" \"rgb L\" [0.3 0.35 0.4]\n"
            "LightSource \"spot\" \"point3 from\" [2 3 -1] \"point3 to\" [0 0 0] "
            "\"float coneangle\" 50 \"rgb I\" [8 8 8]\n"
            "AttributeBegin\n"
            "  AreaLightSource \"diffuse\" \"rgb L\" [6 6 6]\n"
            "  Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] "
            "\"point3 P\" [-1 3 -1  1 3 -1  1 3 1  -1 3 1]\n"
            "AttributeEnd\n"
            "Material \"diffuse\" \"rgb reflectance\" [0.6 0.5 0.4]\n"
            "Shape \"trianglemesh\" \"integer indices\" [0 1 2 0 2 3] "
            "\"point3 P\" [-5 0 -5  -5 0 5  5 0 5  5 0 -5]\n";
    const char *materials[] = {
        "\"diffuse\" \"rgb reflectance\" [0.2 0.7 0.3]",
        "\"conductor\" \"float roughness\" 0.3",
        "\"conductor\" \"float roughness\" 0",
        "\"dielectric\" \"float roughness\" 0",
        "\"dielectric\" \"float roughness\" 0.25",
        "\"fabric\" \"rgb reflectance\" [0.8 0.5 0.3] \"float roughness\" 0.4",
        "\"coateddiffuse\" \"rgb reflectance\" [0.5 0.4 0.3] \"float roughness\" 0.2",
    };
    for (int i = 0; i < int(std::size(materials)); ++i)
        text += fmt::format("AttributeBegin\n  Material {}\n  Translate {} 0.45 {}\n"
                            "  Shape \"sphere\" \"float radius\" 0.45\nAttributeEnd\n",
                            materials[i], -2.5 + i, i % 2 ? 0.6 : -0.4);
    return text;
}

// The densities of one path x[0] (on a light) ... x[n-1] (the camera) as each direction's walk
// would sample its vertices: toCamera[k] is the density of x[k] for a walk from the light,
// toLight[k] for a walk from the camera, per unit area (solid angle at an infinite light).
struct PathDensities {
    std::vector<Float> toCamera, toLight;
};

PathDensities Densities(const BDPTIntegrator &bdpt, const std::vector<BDPTVertex> &x) {
    int n = int(x.size());
    PathDensities d{std::vector<Float>(n, 0), std::vector<Float>(n, 0)};
    d.toCamera[0] = x[0].PDFLightOrigin(bdpt, x[1]);
    for (int k = 1; k < n; ++k)
        d.toCamera[k] = x[k - 1].PDF(bdpt, k >= 2 ? &x[k - 2] : nullptr, x[k]);
    for (int k = 0; k + 1 < n; ++k)
        d.toLight[k] = x[k + 1].PDF(bdpt, k + 2 < n ? &x[k + 2] : nullptr, x[k]);
    return d;
}

// Can strategy (s, t) make the path? It needs an emitter a camera walk can hit (s = 0), or two
// connectible vertices to join.
bool CanMake(const std::vector<BDPTVertex> &x, int s) {
    int n = int(x.size());
    if (s == 0)
        return !x[0].IsDeltaLight() && x[0].lightType != LightType::DeltaDirection;
    return x[s - 1].IsConnectible() && (s == n - 1 || x[s].IsConnectible());
}

// The weight strategy (s, n - s) gives the path: its subpaths hold the path's vertices with the
// densities of their own walks' direction.
Float StrategyWeight(const BDPTIntegrator &bdpt, const std::vector<BDPTVertex> &x,
                     const PathDensities &d, int s) {
    int n = int(x.size()), t = n - s;
    std::vector<BDPTVertex> light(x.begin(), x.begin() + s), camera;
    for (int k = 0; k < s; ++k) {
        light[k].pdfFwd = d.toCamera[k];
        light[k].pdfRev = d.toLight[k];
    }
    for (int k = n - 1; k >= s; --k) {
        camera.push_back(x[k]);
        camera.back().pdfFwd = d.toLight[k];
        camera.back().pdfRev = d.toCamera[k];
    }
    BDPTVertex *sampled = s == 1 ? &light[0] : t == 1 ? &camera[0] : nullptr;
    return BDPTTestAccess::MISWeight(bdpt, light.data(), camera.data(), sampled, s, t);
}

const char *TypeName(VertexType type) {
    const char *names[] = {"camera", "light", "surface", "medium"};
    return names[int(type)];
}

// The path's vertices, for messages.
std::string DescribePath(const std::vector<BDPTVertex> &x) {
    std::string path;
    for (const BDPTVertex &v : x)
        path += fmt::format("{}{}", path.empty() ? "" : ", ", TypeName(v.type)) +
                (v.type == VertexType::Surface ? fmt::format(" {}", v.bsdf->ToString()) : "");
    return path;
}

// The relative difference of a density the walk stored from the one computed afresh.
double RelativeDifference(Float walk, Float fresh) {
    return walk == fresh ? 0 : std::abs(walk - fresh) / std::max(std::abs(walk), std::abs(fresh));
}

// The walks' own densities against fresh ones, where the walk that made a vertex saw both its
// neighbours, by kind: "light subpath, medium vertex, pdfRev" and the like. The walks take their
// directions from the rays they traced, the fresh ones from the vertices' positions; rays leave
// from origins offset off the surface (1e-4 of the scene's scale), so the two differ slightly
// where segments are short or meet a surface at a grazing angle. A wrong conversion (a missing
// cosine or distance, the wrong mode or neighbour) is off on most vertices of its kind.
using DensityDifferences = std::map<std::string, std::vector<double>>;
constexpr const char *kLayeredKind = "through a layered BSDF";

void CompareWalkDensities(const std::vector<BDPTVertex> &x, int s, const PathDensities &d,
                          DensityDifferences *differences) {
    int n = int(x.size());
    // through: the vertex whose BSDF gave the density. A layered BSDF's density is an estimate
    // seeded by its exact directions, which the fresh ones (from positions) do not repeat: its
    // densities are two kinds of their own, pdfFwd and pdfRev "through a layered BSDF".
    auto add = [&](const char *subpath, int k, const char *which, int through, Float walk, Float fresh) {
        bool layered = through >= 0 && through < n && x[through].type == VertexType::Surface &&
                       x[through].bsdf->ToString().find("Coated") != std::string::npos;
        std::string kind = layered ? fmt::format("{}, {}", which, kLayeredKind)
                                   : fmt::format("{} subpath, {} vertex, {}", subpath,
                                                 TypeName(x[k].type), which);
        (*differences)[kind].push_back(RelativeDifference(walk, fresh));
    };
    // (A delta light's origin density is 0 by pbrt-v4's convention and the light's probability
    // in the walk; no weight reads it, since no strategy can hit such a light.)
    for (int k = x[0].IsDeltaLight() ? 1 : 0; k < s; ++k) {
        add("light", k, "pdfFwd", k - 1, x[k].pdfFwd, d.toCamera[k]);
        if (k + 2 < s)
            add("light", k, "pdfRev", k + 1, x[k].pdfRev, d.toLight[k]);
    }
    for (int k = s + 1; k + 1 < n; ++k) {
        add("camera", k, "pdfFwd", k + 1, x[k].pdfFwd, d.toLight[k]);
        if (k >= s + 2)
            add("camera", k, "pdfRev", k - 1, x[k].pdfRev, d.toCamera[k]);
    }
}

class BDPTMISWeights : public testing::TestWithParam<Variant> {};

// Thresholds: each path's weights sum to 1 within 1e-3 (float arithmetic over up to nine density
// ratios; a strategy left out or counted twice, or a wrong density, is off by far more). For
// each kind of walk density, the median differs from the fresh one by less than 0.1 % and 90 %
// of them by less than 1 % (measured: medians up to 1.3e-4, 90th percentiles up to 3.7e-3, from
// the offsets; a density 10 % off for one kind of vertex fails). A layered BSDF's densities are
// estimates, which the offsets reseed: their median differs by less than 30 % (measured 8-14 %;
// a walk that stores its sample's proportional pdf instead, 80-87 %). Fixed seeds.
TEST_P(BDPTMISWeights, SumToOneOnEveryPathAndTheWalksStoreTheirDensities) {
    const Variant &v = GetParam();
    std::filesystem::path folder = TestFolder(std::string("bdptmis_") + v.name);
    std::string file = (folder / "scene.pbrt").string();
    std::ofstream(file) << SceneText(v);
    std::unique_ptr<Scene> scene = LoadScene(file, {});
    BDPTIntegrator bdpt(*scene, scene->integratorOptions);
    int maxDepth = BDPTTestAccess::MaxDepth(bdpt);
    std::vector<BDPTVertex> cameraPath(maxDepth + 2), lightPath(maxDepth + 1);

    int paths = 0, delta = 0, medium = 0, fromSpot = 0, fromSky = 0, fromArea = 0;
    double worstSum = 0;
    DensityDifferences walkDensities;
    Bounds2i pixels = scene->film.PixelBounds();
    Vector2i size = pixels.Diagonal();
    Sampler sampler = scene->sampler;
    for (int index = 0; index < 40000; ++index) {
        Point2i p = pixels.pMin + Vector2i(index % size.x, (index / 7) % size.y);
        sampler.StartPixelSample(p, index);
        SampledWavelengths lambda = scene->film.SampleWavelengths(sampler.Get1D());
        CameraSample cs = GetCameraSample(sampler, p, scene->film.GetFilter(), false);
        pstd::optional<CameraRayDifferential> ray = scene->GenerateCameraRay(cs, 1);
        ASSERT_TRUE(ray);
        int nCamera = BDPTTestAccess::CameraSubpath(bdpt, ray->ray, lambda, sampler, cameraPath.data());
        int nLight = BDPTTestAccess::LightSubpath(bdpt, lambda, sampler, ray->ray.time, lightPath.data());
        // The path: the light subpath up to its last connectible vertex, joined to the camera
        // subpath up to its last connectible surface or medium vertex.
        int t = nCamera;
        while (t >= 2 && (cameraPath[t - 1].type == VertexType::Light || !cameraPath[t - 1].IsConnectible()))
            --t;
        int s = nLight;
        while (s >= 1 && !lightPath[s - 1].IsConnectible())
            --s;
        if (t < 2 || s < 1 || s + t - 2 > maxDepth)
            continue;
        std::vector<BDPTVertex> x(lightPath.begin(), lightPath.begin() + s);
        for (int k = t - 1; k >= 0; --k)
            x.push_back(cameraPath[k]);
        PathDensities d = Densities(bdpt, x);
        CompareWalkDensities(x, s, d, &walkDensities);

        double sum = 0;
        for (int split = 0; split < s + t; ++split)
            if (CanMake(x, split))
                sum += StrategyWeight(bdpt, x, d, split);
        worstSum = std::max(worstSum, std::abs(sum - 1));
        ASSERT_NEAR(sum, 1, 1e-3) << "a path of " << s << " light and " << t << " camera vertices; "
                                  << DescribePath(x);
        ++paths;
        for (const BDPTVertex &vertex : x) {
            delta += vertex.delta;
            medium += vertex.type == VertexType::Medium;
        }
        fromSpot += x[0].IsDeltaLight();
        fromSky += x[0].IsInfiniteLight();
        fromArea += x[0].lightType == LightType::Area;
    }
    std::printf("%s: %d paths, worst |sum - 1| %.2e; %d specular and %d medium vertices; paths "
                "from the spot light %d, the area light %d, the sky %d\n",
                v.name, paths, worstSum, delta, medium, fromSpot, fromArea, fromSky);
    for (auto &[kind, differences] : walkDensities) {
        std::sort(differences.begin(), differences.end());
        double median = differences[differences.size() / 2];
        double p90 = differences[differences.size() * 9 / 10];
        std::printf("  walk densities, %s: %zu, median difference %.1e, 90th percentile %.1e\n",
                    kind.c_str(), differences.size(), median, p90);
        if (kind.find(kLayeredKind) != std::string::npos) {
            EXPECT_LT(median, 0.3) << kind;
        } else {
            EXPECT_LT(median, 1e-3) << kind;
            EXPECT_LT(p90, 1e-2) << kind;
        }
    }
    // Every kind of vertex the weights treat differently was met.
    EXPECT_GT(paths, 10000);
    EXPECT_EQ(walkDensities.size(), v.fog ? 12u : 8u);
    EXPECT_GT(delta, 100);
    EXPECT_GT(fromSpot, 100);
    EXPECT_GT(fromArea, 100);
    EXPECT_GT(fromSky, 100);
    if (v.fog) {
        EXPECT_GT(medium, 1000);
    }
}

INSTANTIATE_TEST_SUITE_P(Scenes, BDPTMISWeights,
                         testing::Values(Variant{"surfaces", false, false},
                                         Variant{"crop_window", true, false},
                                         Variant{"fog", false, true}),
                         [](const testing::TestParamInfo<Variant> &param) { return param.param.name; });

}  // namespace
}  // namespace pbrt
