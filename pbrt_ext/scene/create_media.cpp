// Media from MakeNamedMedium entities (pbrt-v4's Medium::Create and the Create of each type),
// with pbrt-v4's parameter names and defaults. Where pbrt-v4 accepts what cannot be a medium
// (a negative or NaN coefficient, an unknown preset), this is an error at the parameter.
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/media/scatteringpresets.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <cmath>
#include <string>
#include <utility>

namespace pbrt {

namespace {

const FileLoc &LocOf(const ParameterDictionary &p, const std::string &name, const FileLoc &def) {
    const FileLoc *loc = p.Loc(name);
    return loc ? *loc : def;
}

// A scattering coefficient: finite and non-negative at every wavelength.
Spectrum Coefficient(const ParameterDictionary &p, const std::string &name,
                     const std::string &folder) {
    Spectrum s = GetSpectrum(p, name, Spectrum(1.f), SpectrumType::Unbounded, folder);
    for (Float v : DenselySample(s).values)
        if (!(v >= 0) || !std::isfinite(v))
            throw ParseError(*p.Loc(name), "medium \"" + name +
                                               "\" must be finite and non-negative at every "
                                               "wavelength");
    return s;
}

Float NonNegative(const ParameterDictionary &p, const std::string &name, Float def,
                  const FileLoc &loc) {
    Float v = p.GetOneFloat(name, def);
    if (!(v >= 0) || !std::isfinite(v))
        throw ParseError(LocOf(p, name, loc), fmt::format("medium \"{}\" is {}; expected a finite "
                                                          "value >= 0",
                                                          name, v));
    return v;
}

Float PhaseAsymmetry(const ParameterDictionary &p, const FileLoc &loc) {
    Float g = p.GetOneFloat("g", 0);
    if (!(g > -1 && g < 1))
        throw ParseError(LocOf(p, "g", loc),
                         fmt::format("medium \"g\" is {}; expected -1 < g < 1", g));
    return g;
}

// sigma_a and sigma_s: a preset's measurements, or the parameters (1 when absent).
std::pair<Spectrum, Spectrum> ScatteringCoefficients(const ParameterDictionary &p,
                                                     const std::string &folder) {
    std::string preset = p.GetOneString("preset", "");
    if (preset.empty())
        return {Coefficient(p, "sigma_a", folder), Coefficient(p, "sigma_s", folder)};
    if (std::optional<std::pair<Spectrum, Spectrum>> measured = MeasuredScattering(preset))
        return *measured;
    throw ParseError(*p.Loc("preset"), "unknown medium preset \"" + preset + "\"; expected one of " +
                                           MeasuredScatteringNames());
}

// The Le spectrum and the factor that makes it 1 nit (pbrt-v4 divides by its photometric
// integral), or zero emission.
std::pair<Spectrum, Float> Emission(const ParameterDictionary &p, const std::string &folder) {
    Spectrum Le = GetSpectrum(p, "Le", Spectrum(0.f), SpectrumType::Illuminant, folder);
    if (!(Le.MaxValue() > 0))
        return {Spectrum(0.f), 0};
    return {Le, 1 / SpectrumToPhotometric(Le)};
}

// A grid's values: nx * ny * nz of them, finite and non-negative.
template <typename T, typename Check>
SampledGrid<T> Grid(const ParameterDictionary &p, const std::string &name, std::vector<T> values,
                    int nx, int ny, int nz, const FileLoc &loc, Check isValid) {
    const FileLoc &at = LocOf(p, name, loc);
    if (int64_t(values.size()) != int64_t(nx) * ny * nz)
        throw ParseError(at, "grid medium has " + std::to_string(values.size()) + " \"" + name +
                                 "\" values; expected nx*ny*nz = " +
                                 std::to_string(int64_t(nx) * ny * nz));
    for (const T &v : values)
        if (!isValid(v))
            throw ParseError(at, "grid medium \"" + name +
                                     "\" has a negative or non-finite value; expected values "
                                     ">= 0");
    return SampledGrid<T>(std::move(values), nx, ny, nz);
}

bool IsValidDensity(Float v) { return v >= 0 && std::isfinite(v); }
bool IsValidRGB(const RGB &c) {
    return IsValidDensity(c.r) && IsValidDensity(c.g) && IsValidDensity(c.b);
}

struct GridShape {
    int nx, ny, nz;
    Bounds3f bounds;
};

GridShape ReadGridShape(const ParameterDictionary &p, const FileLoc &loc) {
    GridShape g{p.GetOneInt("nx", 1), p.GetOneInt("ny", 1), p.GetOneInt("nz", 1),
                Bounds3f(p.GetOnePoint3f("p0", Point3f(0, 0, 0)),
                         p.GetOnePoint3f("p1", Point3f(1, 1, 1)))};
    for (auto [name, n] : {std::pair{"nx", g.nx}, std::pair{"ny", g.ny}, std::pair{"nz", g.nz}})
        if (n < 1)
            throw ParseError(LocOf(p, name, loc), std::string("grid medium \"") + name +
                                                      "\" must be at least 1");
    if (g.bounds.IsDegenerate() || g.bounds.Volume() <= 0)
        throw ParseError(LocOf(p, "p0", loc),
                         "grid medium bounds p0, p1 enclose no volume; expected p0 < p1");
    return g;
}

HomogeneousMedium CreateHomogeneous(const ParameterDictionary &p, const FileLoc &loc,
                                    const std::string &folder) {
    auto [sigma_a, sigma_s] = ScatteringCoefficients(p, folder);
    auto [Le, toNits] = Emission(p, folder);
    Float LeScale = NonNegative(p, "Lescale", 1, loc) * toNits;
    return HomogeneousMedium(sigma_a, sigma_s, NonNegative(p, "scale", 1, loc), Le, LeScale,
                             PhaseAsymmetry(p, loc));
}

GridMedium CreateUniformGrid(const ParameterDictionary &p, const Transform &renderFromMedium,
                             const FileLoc &loc, const std::string &folder) {
    GridShape shape = ReadGridShape(p, loc);
    std::vector<Float> density = p.GetFloatArray("density");
    if (density.empty())
        throw ParseError(loc, "grid medium needs \"float density\" values");
    auto grid = [&](const std::string &name, std::vector<Float> values) {
        return Grid(p, name, std::move(values), shape.nx, shape.ny, shape.nz, loc,
                    IsValidDensity);
    };
    GridEmission emission;
    auto [Le, toNits] = Emission(p, folder);
    std::vector<Float> temperature = p.GetFloatArray("temperature");
    if (!temperature.empty()) {
        if (Le.MaxValue() > 0)
            throw ParseError(LocOf(p, "Le", loc),
                             "grid medium has both \"Le\" and \"temperature\"; expected one");
        emission.temperature = grid("temperature", std::move(temperature));
        emission.temperatureOffset = p.GetOneFloat(
            "temperatureoffset", p.GetOneFloat("temperaturecutoff", 0));
        emission.temperatureScale = p.GetOneFloat("temperaturescale", 1);
    }
    emission.Le = Le;
    std::vector<Float> LeScale = p.GetFloatArray("Lescale");
    for (Float &s : LeScale)
        s *= toNits;
    emission.LeScale = LeScale.empty() ? SampledGrid<Float>({toNits}, 1, 1, 1)
                                       : grid("Lescale", std::move(LeScale));
    auto [sigma_a, sigma_s] = ScatteringCoefficients(p, folder);
    return GridMedium(shape.bounds, renderFromMedium, sigma_a, sigma_s,
                      NonNegative(p, "scale", 1, loc), PhaseAsymmetry(p, loc),
                      grid("density", std::move(density)), std::move(emission));
}

RGBGridMedium CreateRGBGrid(const ParameterDictionary &p, const Transform &renderFromMedium,
                            const FileLoc &loc) {
    GridShape shape = ReadGridShape(p, loc);
    std::vector<RGB> sigma_a = p.GetRGBArray("sigma_a"), sigma_s = p.GetRGBArray("sigma_s"),
                     Le = p.GetRGBArray("Le");
    if (sigma_a.empty() && sigma_s.empty())
        throw ParseError(loc, "rgbgrid medium needs \"rgb sigma_a\" and/or \"rgb sigma_s\"");
    if (!Le.empty() && sigma_a.empty())
        throw ParseError(LocOf(p, "Le", loc), "rgbgrid medium with \"Le\" needs \"sigma_a\"");
    const RGBColorSpace &cs = p.ColorSpace();
    auto grid = [&]<typename S>(const std::string &name, const std::vector<RGB> &values)
        -> std::optional<SampledGrid<S>> {
        if (values.empty())
            return {};
        Grid(p, name, values, shape.nx, shape.ny, shape.nz, loc, IsValidRGB);  // checks only
        std::vector<S> spectra;
        spectra.reserve(values.size());
        for (const RGB &rgb : values)
            spectra.push_back(S(cs, rgb));
        return SampledGrid<S>(std::move(spectra), shape.nx, shape.ny, shape.nz);
    };
    return RGBGridMedium(shape.bounds, renderFromMedium, PhaseAsymmetry(p, loc),
                         grid.template operator()<RGBUnboundedSpectrum>("sigma_a", sigma_a),
                         grid.template operator()<RGBUnboundedSpectrum>("sigma_s", sigma_s),
                         NonNegative(p, "scale", 1, loc),
                         grid.template operator()<RGBIlluminantSpectrum>("Le", Le),
                         NonNegative(p, "Lescale", 1, loc));
}

CloudMedium CreateCloud(const ParameterDictionary &p, const Transform &renderFromMedium,
                        const FileLoc &loc, const std::string &folder) {
    Bounds3f bounds(p.GetOnePoint3f("p0", Point3f(0, 0, 0)), p.GetOnePoint3f("p1", Point3f(1, 1, 1)));
    if (bounds.Volume() <= 0)
        throw ParseError(LocOf(p, "p0", loc),
                         "cloud medium bounds p0, p1 enclose no volume; expected p0 < p1");
    return CloudMedium(bounds, renderFromMedium, Coefficient(p, "sigma_a", folder),
                       Coefficient(p, "sigma_s", folder), PhaseAsymmetry(p, loc),
                       NonNegative(p, "density", 1, loc), NonNegative(p, "wispiness", 1, loc),
                       NonNegative(p, "frequency", 5, loc));
}

NanoVDBMedium CreateNanoVDB(const ParameterDictionary &p, const Transform &renderFromMedium,
                            const FileLoc &loc, const std::string &folder) {
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty())
        throw ParseError(loc, "nanovdb medium needs a \"string filename\"");
    const FileLoc &at = LocOf(p, "filename", loc);
    Spectrum sigma_a = Coefficient(p, "sigma_a", folder), sigma_s = Coefficient(p, "sigma_s", folder);
    std::string path = ResolvePath(folder, filename);
    try {
        CheckMemory(at, "the grids of \"" + filename + "\"", NanoVDBMedium::GridBytes(path));
        return NanoVDBMedium(path, p.GetOneString("gridname", "density"),
                             p.GetOneString("temperaturename", "temperature"), renderFromMedium,
                             sigma_a, sigma_s, NonNegative(p, "scale", 1, loc),
                             PhaseAsymmetry(p, loc), NonNegative(p, "Lescale", 1, loc),
                             p.GetOneFloat("temperatureoffset",
                                           p.GetOneFloat("temperaturecutoff", 0)),
                             p.GetOneFloat("temperaturescale", 1));
    } catch (const ParseError &) {
        throw;  // the memory check's, located already
    } catch (const std::runtime_error &e) {
        throw ParseError(at, e.what());
    }
}

}  // namespace

Medium CreateMedium(const TransformedSceneEntity &e, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::string type = p.GetOneString("type", "");
    auto create = [&]() -> Medium {
        if (type == "homogeneous")
            return CreateHomogeneous(p, e.loc, folder);
        if (type == "uniformgrid")
            return CreateUniformGrid(p, e.worldFromObject, e.loc, folder);
        if (type == "rgbgrid")
            return CreateRGBGrid(p, e.worldFromObject, e.loc);
        if (type == "cloud")
            return CreateCloud(p, e.worldFromObject, e.loc, folder);
        if (type == "nanovdb")
            return CreateNanoVDB(p, e.worldFromObject, e.loc, folder);
        throw ParseError(LocOf(p, "type", e.loc),
                         "unknown medium type \"" + type +
                             "\"; expected homogeneous, uniformgrid, rgbgrid, cloud or nanovdb");
    };
    Medium medium = create();
    p.ReportUnused();
    return medium;
}

}  // namespace pbrt
