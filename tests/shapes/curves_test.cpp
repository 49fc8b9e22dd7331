// Curves: the spline conversions keep the curve; Embree's flat, round and normal-oriented curves
// agree with dense, independently built tessellations of the same surfaces in hit rate and hit
// distance on random rays; the interaction has pbrt-v4's u, v and frame; a fabric on a curve
// takes the tangent as its thread direction and its sampling passes chi-square there; bad curves
// are errors.
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/shapes/aggregate.h"
#include "pbrt_ext/shapes/curves.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
#include "pbrt_ext/util/splines.h"

#include "tests/support/chi2.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <functional>
#include <stdexcept>

namespace pbrt {
namespace {

Float Uniform(RNG &rng) { return rng.Uniform<Float>(); }

TEST(Splines, BSplineAndQuadraticConversionsKeepTheCurve) {
    std::array<Point3f, 4> p = {Point3f(0, 0, 0), Point3f(1, 2, 0), Point3f(3, -1, 1),
                                Point3f(4, 0, 2)};
    std::array<Point3f, 4> bezier = CubicBSplineToBezier(p);
    for (Float t : {0.f, 0.25f, 0.6f, 1.f}) {
        // The uniform cubic B-spline's basis functions, written out.
        Float b0 = (1 - t) * (1 - t) * (1 - t) / 6, b1 = (3 * t * t * t - 6 * t * t + 4) / 6,
              b2 = (-3 * t * t * t + 3 * t * t + 3 * t + 1) / 6, b3 = t * t * t / 6;
        Vector3f expected = b0 * Vector3f(p[0]) + b1 * Vector3f(p[1]) + b2 * Vector3f(p[2]) +
                            b3 * Vector3f(p[3]);
        EXPECT_LT(Distance(EvaluateCubicBezier(bezier, t), Point3f(expected)), 1e-5f) << t;
    }
    std::array<Point3f, 3> q = {Point3f(0, 0, 0), Point3f(1, 2, 0), Point3f(2, 0, 1)};
    std::array<Point3f, 4> cubic = ElevateQuadraticBezierToCubic(q);
    for (Float t : {0.f, 0.3f, 0.5f, 1.f}) {
        Vector3f expected = (1 - t) * (1 - t) * Vector3f(q[0]) + 2 * t * (1 - t) * Vector3f(q[1]) +
                            t * t * Vector3f(q[2]);
        EXPECT_LT(Distance(EvaluateCubicBezier(cubic, t), Point3f(expected)), 1e-5f) << t;
    }
}

// One S-shaped cubic segment about 4 long, in the xz plane, of constant width 0.2.
CurveDescription OneCurve(CurveType type) {
    CurveDescription c;
    c.p = {Point3f(-2, 0, 0), Point3f(-1, 0, 1.5f), Point3f(1, 0, -1.5f), Point3f(2, 0, 0)};
    c.type = type;
    c.width0 = c.width1 = 0.2f;
    if (type == CurveType::Ribbon)  // in the curve's plane: the ribbon spans y as it bends
        c.n = {Normal3f(-1.5f, 0, 1), Normal3f(-1.5f, 0, 1)};
    return c;
}

// A strip or tube around the curve: at each of `along` steps, a cross-section from
// crossSection(u, centre, tangent) (closed polygon points), joined into triangles.
std::shared_ptr<TriangleMesh> Sweep(
    const CurveMesh &curve, int along, int around, bool closed,
    const std::function<Point3f(Float u, Point3f c, Vector3f t, int k)> &crossSection) {
    std::array<Point3f, 4> cp = {curve.cp[0], curve.cp[1], curve.cp[2], curve.cp[3]};
    std::vector<Point3f> p;
    std::vector<int> indices;
    for (int i = 0; i <= along; ++i) {
        Float u = Float(i) / along;
        Vector3f t;
        Point3f c = EvaluateCubicBezier(cp, u, &t);
        for (int k = 0; k < around; ++k)
            p.push_back(crossSection(u, c, Normalize(t), k));
    }
    int ring = closed ? around : around - 1;
    for (int i = 0; i < along; ++i)
        for (int k = 0; k < ring; ++k) {
            int a = i * around + k, b = i * around + (k + 1) % around;
            int c = a + around, d = b + around;
            indices.insert(indices.end(), {a, b, d, a, d, c});
        }
    return std::make_shared<TriangleMesh>(MakeTriangleMesh(Transform(), false, indices, p));
}

struct Agreement {
    int rays = 0, bothHit = 0, disagree = 0;
    std::vector<double> dt;  // |t difference| where both hit
};

// Rays from points around the curve toward random points near its middle part.
Agreement Compare(const CurveMesh &curve, const TriangleMesh &reference,
                  const std::function<Vector3f(RNG &)> &direction) {
    EmbreeAggregate curves, mesh;
    curves.AddCurves(std::make_shared<CurveMesh>(curve), {0, -1});
    curves.Commit();
    mesh.AddTriangleMesh(std::make_shared<TriangleMesh>(reference), {0, -1});
    mesh.Commit();
    std::array<Point3f, 4> cp = {curve.cp[0], curve.cp[1], curve.cp[2], curve.cp[3]};
    RNG rng(19);
    Agreement a;
    for (; a.rays < 20000; ++a.rays) {
        Point3f target = EvaluateCubicBezier(cp, 0.1f + 0.8f * Uniform(rng)) +
                         0.15f * Vector3f(Uniform(rng) - 0.5f, Uniform(rng) - 0.5f,
                                          Uniform(rng) - 0.5f);
        Vector3f d = direction(rng);
        Ray ray(target - 5 * d, d);
        pstd::optional<ShapeIntersection> h1 = curves.Intersect(ray), h2 = mesh.Intersect(ray);
        if (bool(h1) != bool(h2))
            ++a.disagree;
        else if (h1) {
            ++a.bothHit;
            a.dt.push_back(std::abs(h1->tHit - h2->tHit));
        }
    }
    return a;
}

Vector3f AnyDirection(RNG &rng) { return SampleUniformSphere(Point2f(Uniform(rng), Uniform(rng))); }

// Thresholds (seeded rays): at most 1 % of the rays disagree (those that graze the outline,
// where the tessellation's chords and Embree's own refinement differ) and at least 20 % hit;
// where both hit, 99.9 % of the distances agree to a fiftieth of the width (0.004), and all
// to within the radius (a ray that grazes the surface may meet the two on different sides).
void ExpectAgreement(Agreement a) {
    EXPECT_LE(a.disagree, a.rays / 100) << a.disagree << " of " << a.rays;
    EXPECT_GE(a.bothHit, a.rays / 5);
    std::sort(a.dt.begin(), a.dt.end());
    ASSERT_FALSE(a.dt.empty());
    EXPECT_LT(a.dt[a.dt.size() * 999 / 1000], 0.004);
    EXPECT_LT(a.dt.back(), 0.1);
}

TEST(Curves, RoundCurveMatchesADenseTube) {
    CurveMesh curve = MakeCurveMesh(Transform(), false, OneCurve(CurveType::Cylinder));
    // The curve lies in the xz plane, so y and y x t make a frame that turns smoothly with it.
    auto tube = Sweep(curve, 800, 64, true, [](Float, Point3f c, Vector3f t, int k) {
        Vector3f x(0, 1, 0), y = Normalize(Cross(t, x));
        Float phi = 2 * Pi * k / 64;
        return c + 0.1f * (std::cos(phi) * x + std::sin(phi) * y);
    });
    ExpectAgreement(Compare(curve, *tube, AnyDirection));
}

TEST(Curves, FlatCurveFacesTheRayAsADenseStripDoes) {
    // Parallel rays: the strip that faces them all is one mesh.
    Vector3f d = Normalize(Vector3f(0.3f, 1, -0.2f));
    CurveMesh curve = MakeCurveMesh(Transform(), false, OneCurve(CurveType::Flat));
    auto strip = Sweep(curve, 800, 2, false, [&](Float, Point3f c, Vector3f t, int k) {
        return c + (k ? 0.1f : -0.1f) * Normalize(Cross(d, t));
    });
    ExpectAgreement(Compare(curve, *strip, [&](RNG &) { return d; }));
}

// Embree's normal-oriented curves are built for ribbons that bend across their face (grass)
// and twist a little along each segment; both are compared, the twist at 30 degrees per
// segment (Embree's band only approximately follows the normals' interpolation, and departs
// from it by more at larger twists).
TEST(Curves, RibbonFollowsItsNormalsAsADenseStripDoes) {
    CurveDescription twisted = OneCurve(CurveType::Ribbon);
    twisted.p = {Point3f(-2, 0, 0), Point3f(-0.7f, 0, 0), Point3f(0.7f, 0, 0), Point3f(2, 0, 0)};
    twisted.n = {Normal3f(0, 0, 1), Normal3f(0, 0.5f, 0.866f)};
    for (const CurveDescription &c : {OneCurve(CurveType::Ribbon), twisted}) {
        CurveMesh curve = MakeCurveMesh(Transform(), false, c);
        Vector3f n0(curve.n[0]), n1(curve.n[1]);
        auto strip = Sweep(curve, 800, 2, false, [&](Float u, Point3f p, Vector3f t, int k) {
            Vector3f n = Normalize((1 - u) * n0 + u * n1);
            return p + (k ? 0.1f : -0.1f) * Normalize(Cross(n, t));
        });
        ExpectAgreement(Compare(curve, *strip, AnyDirection));
    }
}

TEST(Curves, InteractionHasPbrtV4sUVAndFrame) {
    // A straight flat curve along x of width 0.4 at z = 0, seen from above.
    CurveDescription c;
    c.p = {Point3f(0, 0, 0), Point3f(1, 0, 0), Point3f(2, 0, 0), Point3f(3, 0, 0)};
    c.width0 = c.width1 = 0.4f;
    for (CurveType type : {CurveType::Flat, CurveType::Cylinder}) {
        c.type = type;
        CurveMesh curve = MakeCurveMesh(Transform(), false, c);
        Ray ray(Point3f(1.5f, 0.1f, 5), Vector3f(0, 0, -1));
        SurfaceInteraction si = CurveInteraction(curve, 0, 0.5f, ray, 5);
        EXPECT_NEAR(si.uv.x, 0.5f, 1e-5f);
        // across = d x dpdu = (0, 0, -1) x (1, 0, 0) = (0, -1, 0): y = +0.1 is v = 0.25.
        EXPECT_NEAR(si.uv.y, 0.25f, 1e-5f);
        EXPECT_NEAR(Dot(Normalize(si.dpdu), Vector3f(1, 0, 0)), 1, 1e-5f);
        EXPECT_NEAR(Dot(si.dpdu, si.dpdv), 0, 1e-4f);
        EXPECT_NEAR(si.errorBound, 0.4f, 1e-6f);
        if (type == CurveType::Flat)
            EXPECT_NEAR(std::abs(si.n.z), 1, 1e-5f);  // the strip faces the ray
        else  // a quarter of the way across, the normal has turned 45 degrees toward +y
            EXPECT_NEAR(std::abs(si.n.y), std::sqrt(0.5f), 1e-4f);
    }
}

std::string WriteScene(const std::string &name, const std::string &text) {
    std::filesystem::path dir = std::filesystem::temp_directory_path() / "pbrt_ext_curves_test";
    std::filesystem::create_directories(dir);
    std::filesystem::path file = dir / name;
    std::ofstream(file) << text;
    return file.string();
}

TEST(Curves, FabricOnACurveTakesTheTangentAsItsThread) {
    std::string file = WriteScene("yarn.pbrt", R"(LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective"
Film "rgb" "integer xresolution" 4 "integer yresolution" 4
WorldBegin
Material "fabric" "rgb reflectance" [0.7 0.5 0.3] "float roughness" 0.3
Shape "curve" "point3 P" [-1 -1 0  0 -0.5 0.3  0.5 0.5 0.3  1 1 0] "float width" 0.3
    "string type" "cylinder"
)");
    RenderOverrides overrides;
    overrides.quiet = true;
    std::unique_ptr<Scene> scene = LoadScene(file, overrides);
    RNG rng(23);
    int tested = 0;
    for (int i = 0; i < 40 && tested < 3; ++i) {
        Point3f o(Uniform(rng) - 0.5f, Uniform(rng) - 0.5f, 5);
        pstd::optional<ShapeIntersection> hit = scene->Intersect(Ray(o, Vector3f(0, 0, -1)));
        if (!hit)
            continue;
        ++tested;
        SampledWavelengths lambda = SampledWavelengths::SampleVisible(0.5f);
        BSDF bsdf = scene->materials[hit->intr.materialIndex].GetBSDF(hit->intr, lambda);
        Vector3f thread = bsdf.LocalToRender(Vector3f(1, 0, 0));
        EXPECT_NEAR(AbsDot(thread, Normalize(hit->intr.shading.dpdu)), 1, 1e-4f);
        Vector3f wo = hit->intr.wo;
        auto sample = [&](Point2f u, Float uc) -> pstd::optional<Vector3f> {
            pstd::optional<BSDFSample> bs = bsdf.Sample_f(wo, uc, u);
            if (!bs || bs->pdf == 0)
                return {};
            return bs->wi;
        };
        Chi2Options opts;
        opts.numTests = 3;
        opts.sampleCount = 300000;
        opts.seed = 29 + tested;
        Chi2Result r = Chi2TestSampler(sample, [&](Vector3f wi) { return bsdf.PDF(wo, wi); }, opts);
        EXPECT_TRUE(r.passed) << r.message;
    }
    EXPECT_EQ(tested, 3);
}

TEST(Curves, BadCurvesAreErrors) {
    CurveDescription c = OneCurve(CurveType::Flat);
    c.degree = 4;
    EXPECT_THROW(MakeCurveMesh(Transform(), false, c), std::runtime_error);
    c = OneCurve(CurveType::Flat);
    c.p.pop_back();
    EXPECT_THROW(MakeCurveMesh(Transform(), false, c), std::runtime_error);
    c = OneCurve(CurveType::Flat);
    c.basis = "hermite";
    EXPECT_THROW(MakeCurveMesh(Transform(), false, c), std::runtime_error);
    c = OneCurve(CurveType::Ribbon);
    c.n.pop_back();
    EXPECT_THROW(MakeCurveMesh(Transform(), false, c), std::runtime_error);
    c = OneCurve(CurveType::Flat);
    c.width1 = -1;
    EXPECT_THROW(MakeCurveMesh(Transform(), false, c), std::runtime_error);
    // A B-spline of 5 points has 2 segments; a Bézier of 7 has 2.
    c = OneCurve(CurveType::Flat);
    c.p.push_back(Point3f(3, 0, 1));
    c.basis = "bspline";
    EXPECT_EQ(MakeCurveMesh(Transform(), false, c).NumSegments(), 2);
}

}  // namespace
}  // namespace pbrt
