// Lights from scene-file entities: pbrt-v4's parameters, transforms and photometric scale (a
// light's spectrum is divided by its luminance, so "scale" is luminance; "power" and
// "illuminance" fix the emitted power where pbrt-v4 defines them).
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/scene/spectra.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/equalarea.h"
#include "pbrt_ext/util/error.h"

#include <array>
#include <cmath>
#include <filesystem>

namespace pbrt {

Spectrum GetSpectrum(const ParameterDictionary &parameters, const std::string &name,
                     Spectrum defaultValue, SpectrumType type, const std::string &folder) {
    std::optional<SpectrumParam> s = parameters.GetOneSpectrum(name);
    return s ? CreateSpectrum(*s, type, parameters.ColorSpace(), folder) : defaultValue;
}

namespace {

// An emission spectrum, the colour space's illuminant by default, and the factor that makes
// it 1 nit: pbrt-v4 divides a light's scale by SpectrumToPhotometric, so that "scale" (and
// "power", "illuminance") are photometric whatever the spectrum's units.
struct Emission {
    Spectrum spectrum;
    Float toNits;
};
Emission GetEmission(const ParameterDictionary &p, const std::string &name, const std::string &folder) {
    Spectrum s = GetSpectrum(p, name, Spectrum::DenselySampled(p.ColorSpace().illuminant),
                             SpectrumType::Illuminant, folder);
    Float nits = SpectrumToPhotometric(s);
    // Tabulated here, so that every triangle of an emissive mesh shares one table.
    return {TabulatedForLookup(s), nits > 0 ? 1 / nits : 0};
}

// What an image light's scale is divided by, so that its texels are 1 nit per unit of the
// colour space's illuminant (pbrt-v4's SpectrumToPhotometric of the illuminant).
Float IlluminantPhotometric(const RGBColorSpace &cs) {
    return SpectrumToPhotometric(Spectrum::DenselySampled(cs.illuminant));
}

// The rotation taking +z to w (columns: a frame around w).
Transform RotationFromZ(Vector3f w) {
    Frame f = Frame::FromZ(Normalize(w));
    return Transform(SquareMatrix<4>(f.x.x, f.y.x, f.z.x, 0, f.x.y, f.y.y, f.z.y, 0, f.x.z,
                                     f.y.z, f.z.z, 0, 0, 0, 0, 1));
}

Light CreateSpotLight(const TransformedSceneEntity &e, Spectrum I, Float scale) {
    const ParameterDictionary &p = e.parameters;
    Float coneAngle = p.GetOneFloat("coneangle", 30), coneDelta = p.GetOneFloat("conedeltaangle", 5);
    Point3f from = p.GetOnePoint3f("from", Point3f(0, 0, 0)),
            to = p.GetOnePoint3f("to", Point3f(0, 0, 1));
    Float power = p.GetOneFloat("power", -1);
    if (power > 0) {
        Float cosFalloffEnd = std::cos(Radians(coneAngle)),
              cosFalloffStart = std::cos(Radians(coneAngle - coneDelta));
        scale *= power / (2 * Pi * (1 - 0.5f * (cosFalloffStart + cosFalloffEnd)));
    }
    Transform worldFromLight = e.worldFromObject * Translate(Vector3f(from)) *
                               RotationFromZ(to - from);
    return SpotLight(worldFromLight, I, scale, coneAngle, coneAngle - coneDelta);
}

// A light's image (goniometric, projection, area): "filename" is required; pixels must be finite.
Image ReadLightImage(const SceneEntity &e, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::string filename = p.GetOneString("filename", "");
    if (filename.empty())
        throw ParseError(e.loc, "LightSource \"" + e.name + "\" needs \"string filename\"");
    std::string path = ResolvePath(folder, filename);
    if (!std::filesystem::is_regular_file(path))
        throw ParseError(*p.Loc("filename"), "cannot open image \"" + filename + "\" (looked for " +
                                                 path + ")");
    Image image = ReadFileAt(*p.Loc("filename"), [&] { return Image::Read(path); });
    for (int y = 0; y < image.Resolution().y; ++y)
        for (int x = 0; x < image.Resolution().x; ++x) {
            RGB v = image.GetChannels(Point2i(x, y));
            if (!IsFinite(v.r) || !IsFinite(v.g) || !IsFinite(v.b))
                throw ParseError(*p.Loc("filename"), "image \"" + filename + "\" has a non-finite pixel at (" +
                                                         std::to_string(x) + ", " + std::to_string(y) +
                                                         "): not suitable as a light");
        }
    return image;
}

// pbrt-v4's "portal": four world-space corners of a rectangle, or none.
std::optional<std::array<Point3f, 4>> GetPortal(const ParameterDictionary &p) {
    if (!p.HasParameter("portal")) return {};
    std::vector<Point3f> points = p.GetPoint3fArray("portal");
    if (points.size() != 4)
        throw ParseError(*p.Loc("portal"), "\"portal\" has " + std::to_string(points.size()) +
                                               " points; expected the rectangle's 4 corners");
    std::array<Point3f, 4> portal = {points[0], points[1], points[2], points[3]};
    if (std::string error = PortalImageInfiniteLight::PortalFrameError(portal); !error.empty())
        throw ParseError(*p.Loc("portal"), error);
    return portal;
}

// A uniform environment behind a portal: a 1x1 image of L's sRGB, as pbrt-v4 makes it.
Image UniformImage(const Spectrum &L) {
    RGB rgb = RGBColorSpace::sRGB().ToRGB(SpectrumToXYZ(L));
    Image image(Point2i(1, 1));
    for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(0, 0), c, rgb[c]);
    return image;
}

// The illuminance an equal-area environment image gives a surface facing +z (pbrt-v4's, for
// "illuminance": the texels above the horizon, luminance times cos theta).
Float UpperHemisphereIlluminance(const Image &image, const RGBColorSpace &cs) {
    Point2i res = image.Resolution();
    RGB lum = cs.LuminanceVector();
    double sum = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x) {
            Vector3f w = EqualAreaSquareToSphere(Point2f((x + 0.5f) / res.x, (y + 0.5f) / res.y));
            if (w.z <= 0) continue;
            RGB v = image.GetChannels(Point2i(x, y));
            sum += (v.r * lum.r + v.g * lum.g + v.b * lum.b) * w.z;
        }
    return Float(sum * 2 * Pi / (double(res.x) * res.y));
}

// An environment image (from "filename", or L's colour behind a portal), as pbrt-v4 reads it:
// square, for the equal-area octahedral mapping.
Image EnvironmentImage(const TransformedSceneEntity &e, const std::string &filename,
                       const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    if (filename.empty())
        return UniformImage(GetSpectrum(p, "L", Spectrum::DenselySampled(p.ColorSpace().illuminant),
                                        SpectrumType::Illuminant, folder));
    if (p.HasParameter("L"))
        throw ParseError(*p.Loc("L"), "an infinite light takes \"L\" or \"filename\", not both");
    Image image = ReadLightImage(e, folder);
    if (image.Resolution().x != image.Resolution().y)
        throw ParseError(*p.Loc("filename"), "environment image \"" + filename + "\" is " +
                                                 std::to_string(image.Resolution().x) + " x " +
                                                 std::to_string(image.Resolution().y) +
                                                 "; expected a square equal-area map");
    return image;
}

Light CreateInfiniteLight(const TransformedSceneEntity &e, Float scale,
                          const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::string filename = p.GetOneString("filename", "");
    std::optional<std::array<Point3f, 4>> portal = GetPortal(p);
    Float illuminance = p.GetOneFloat("illuminance", -1);
    if (filename.empty() && !portal) {
        Emission L = GetEmission(p, "L", folder);
        scale *= L.toNits;
        if (illuminance > 0)
            scale *= illuminance / Pi;  // a uniform sky of radiance 1 gives E = π
        p.ReportUnused();
        return UniformInfiniteLight(L.spectrum, scale);
    }
    Image image = EnvironmentImage(e, filename, folder);
    p.ReportUnused();
    const RGBColorSpace &cs = image.ColorSpace();
    scale /= IlluminantPhotometric(cs);
    if (illuminance > 0)
        scale *= illuminance / UpperHemisphereIlluminance(image, cs);
    if (portal)
        return PortalImageInfiniteLight(e.worldFromObject, image, scale, &cs, *portal);
    return ImageInfiniteLight(e.worldFromObject, std::move(image), scale, &cs);
}


// pbrt-v4's goniometric light: its diagram's pole along light-space +y.
Light CreateGoniometricLight(const TransformedSceneEntity &e, Float scale, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    Emission I = GetEmission(p, "I", folder);
    Image image = ReadLightImage(e, folder);
    Point2i res = image.Resolution();
    if (res.x != res.y)
        throw ParseError(*p.Loc("filename"), "goniometric image is " + std::to_string(res.x) + " x " +
                                                 std::to_string(res.y) +
                                                 "; expected a square equal-area diagram");
    Float power = p.GetOneFloat("power", -1);
    p.ReportUnused();
    Transform swapYZ(SquareMatrix<4>(1, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 1));
    GoniometricLight light(e.worldFromObject * swapYZ, I.spectrum, scale * I.toNits, std::move(image));
    if (power > 0)  // the power of the diagram at this scale is 4 pi times its mean
        light.MultiplyScale(power / (4 * Pi * light.MeanIntensity()));
    return light;
}

// pbrt-v4's projection light: the image's top row toward light-space +y.
Light CreateProjectionLight(const TransformedSceneEntity &e, Float scale, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    Float fov = p.GetOneFloat("fov", 90);
    if (!(fov > 0 && fov < 180))
        throw ParseError(*p.Loc("fov"), "projection \"fov\" is " + std::to_string(fov) +
                                            "; expected degrees in (0, 180)");
    Float power = p.GetOneFloat("power", -1);
    Image image = ReadLightImage(e, folder);
    p.ReportUnused();
    const RGBColorSpace &cs = image.ColorSpace();
    scale /= IlluminantPhotometric(cs);
    Transform worldFromLight = e.worldFromObject * Scale(1, -1, 1);
    ProjectionLight light(worldFromLight, std::move(image), &cs, scale, fov);
    if (power > 0) {
        RGB luminance = cs.LuminanceVector();
        Float k = light.IntegrateOverSolidAngle([&](RGB rgb) {
            return luminance.r * rgb.r + luminance.g * rgb.g + luminance.b * rgb.b;
        });
        light.MultiplyScale(power / k);
    }
    return light;
}

}  // namespace

std::optional<Light> CreateLight(const TransformedSceneEntity &e, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    Float scale = p.GetOneFloat("scale", 1);
    if (e.name == "point") {
        Emission I = GetEmission(p, "I", folder);
        scale *= I.toNits;
        Float power = p.GetOneFloat("power", -1);
        if (power > 0)
            scale *= power / (4 * Pi);
        Point3f from = p.GetOnePoint3f("from", Point3f(0, 0, 0));
        p.ReportUnused();
        return PointLight(e.worldFromObject * Translate(Vector3f(from)), I.spectrum, scale);
    }
    if (e.name == "spot") {
        Emission I = GetEmission(p, "I", folder);
        Light light = CreateSpotLight(e, I.spectrum, scale * I.toNits);
        p.ReportUnused();
        return light;
    }
    if (e.name == "distant") {
        Emission L = GetEmission(p, "L", folder);
        scale *= L.toNits;
        Point3f from = p.GetOnePoint3f("from", Point3f(0, 0, 0)),
                to = p.GetOnePoint3f("to", Point3f(0, 0, 1));
        Float illuminance = p.GetOneFloat("illuminance", -1);
        if (illuminance > 0)
            scale *= illuminance;
        p.ReportUnused();
        // The light arrives from worldFromLight(0, 0, 1): toward `from`, seen from `to`.
        return DistantLight(e.worldFromObject * RotationFromZ(from - to), L.spectrum, scale);
    }
    if (e.name == "infinite")
        return CreateInfiniteLight(e, scale, folder);
    if (e.name == "goniometric")
        return CreateGoniometricLight(e, scale, folder);
    if (e.name == "projection")
        return CreateProjectionLight(e, scale, folder);
    throw ParseError(e.loc, "unknown LightSource \"" + e.name +
                                "\": expected point, spot, goniometric, projection, distant or infinite");
}

AreaLightDescription CreateAreaLight(const SceneEntity &e, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    if (e.name != "diffuse")
        throw ParseError(e.loc, "unknown AreaLightSource \"" + e.name + "\": expected diffuse");
    AreaLightDescription light;
    light.twoSided = p.GetOneBool("twosided", false);
    light.power = p.GetOneFloat("power", -1);
    if (p.HasParameter("filename")) {
        if (p.HasParameter("L"))
            throw ParseError(*p.Loc("L"), "an area light takes \"L\" or \"filename\", not both");
        // pbrt-v4 makes an image's texels 1 nit per unit of the illuminant of the colour space
        // in force; the texels themselves are in the image's.
        Image image = ReadLightImage(e, folder);
        const RGBColorSpace *imageColorSpace = &image.ColorSpace();
        light.image = std::make_shared<const EmissionImage>(std::move(image), imageColorSpace);
        light.scale = p.GetOneFloat("scale", 1) / IlluminantPhotometric(p.ColorSpace());
    } else {
        Emission L = GetEmission(p, "L", folder);
        light.L = L.spectrum;
        light.scale = p.GetOneFloat("scale", 1) * L.toNits;
    }
    p.ReportUnused();
    return light;
}

}  // namespace pbrt
