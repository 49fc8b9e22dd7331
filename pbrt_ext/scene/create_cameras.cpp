// The scene's camera (pbrt-v4's names, parameters and defaults): perspective, orthographic,
// spherical and realistic, placed by the camera transform over the shutter interval.
#include "pbrt_ext/scene/create.h"

#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/floatfile.h"

#include <fmt/format.h>

#include <filesystem>
#include <string>
#include <vector>

namespace pbrt {

namespace {

Bounds2f ScreenWindow(const ParameterDictionary &p, const RGBFilm &film) {
    std::vector<Float> sw = p.GetFloatArray("screenwindow");
    Bounds2f window = DefaultScreenWindow(film.FullResolution());
    Float frame = p.GetOneFloat("frameaspectratio", 0);
    if (frame > 0)
        window = frame > 1 ? Bounds2f(Point2f(-frame, -1), Point2f(frame, 1))
                           : Bounds2f(Point2f(-1, -1 / frame), Point2f(1, 1 / frame));
    if (sw.empty())
        return window;
    if (sw.size() != 4)
        throw ParseError(*p.Loc("screenwindow"), "\"screenwindow\" needs four values");
    return Bounds2f(Point2f(sw[0], sw[2]), Point2f(sw[1], sw[3]));
}

// The camera's placement over its shutter interval.
CameraMotion CameraMotionOf(const CameraSceneEntity &e) {
    const ParameterDictionary &p = e.parameters;
    Float open = p.GetOneFloat("shutteropen", 0), close = p.GetOneFloat("shutterclose", 1);
    return CameraMotion(CreateAnimatedTransform(e.loc, Inverse(e.cameraFromWorld.t[0]),
                                                e.transformStartTime,
                                                Inverse(e.cameraFromWorld.t[1]),
                                                e.transformEndTime, "the camera's transform: "),
                        open, close);
}

// pbrt-v4 reads the lens, frame and screen-window parameters of a spherical camera and has no
// use for them; so they are read here.
SphericalCamera CreateSphericalCamera(const CameraSceneEntity &e, CameraMotion worldFromCamera,
                                      const RGBFilm &film) {
    const ParameterDictionary &p = e.parameters;
    for (const char *unused : {"lensradius", "focaldistance", "frameaspectratio"})
        p.GetOneFloat(unused, 0);
    p.GetFloatArray("screenwindow");
    std::string mapping = p.GetOneString("mapping", "equalarea");
    p.ReportUnused();
    if (mapping != "equalarea" && mapping != "equirectangular")
        throw ParseError(*p.Loc("mapping"), "spherical camera \"mapping\" \"" + mapping +
                                                "\" is unknown; expected equalarea or "
                                                "equirectangular");
    return SphericalCamera(std::move(worldFromCamera), film.FullResolution(),
                           mapping == "equalarea" ? SphericalCamera::Mapping::EqualArea
                                                  : SphericalCamera::Mapping::EquiRectangular);
}

// The lens file at path (LensFromDescription), its stop set by "aperturediameter"; `what`
// names the file in errors.
std::vector<LensElementInterface> ReadLens(const ParameterDictionary &p, const FileLoc &loc,
                                           const std::string &path, const std::string &what) {
    std::vector<double> values = ReadFloatFile(path, loc, what, kLensDescriptionFormat);
    Float stopDiameter = p.GetOneFloat("aperturediameter", 1);
    if (!(stopDiameter > 0))
        throw ParseError(*p.Loc("aperturediameter"),
                         fmt::format("\"aperturediameter\" {} is not positive", stopDiameter));
    bool clamped = false;
    std::vector<LensElementInterface> lens;
    try {
        lens = LensFromDescription(values, stopDiameter, &clamped);
    } catch (const std::invalid_argument &error) {
        throw ParseError(loc, what + " " + error.what());
    }
    if (clamped)
        WarningAt(*p.Loc("aperturediameter"),
                  "aperture diameter %g mm is greater than the lens's stop allows; clamped", stopDiameter);
    return lens;
}

// "aperture": one of pbrt-v4's built-in diaphragm shapes, or an image of one.
std::optional<ApertureShape> CreateApertureShape(const ParameterDictionary &p,
                                                 const std::string &folder) {
    std::string name = p.GetOneString("aperture", "");
    if (name.empty()) return std::nullopt;
    if (std::optional<ApertureShape> shape = ApertureShape::BuiltIn(name)) return shape;
    std::string path = ResolvePath(folder, name);
    if (!std::filesystem::is_regular_file(path))
        throw ParseError(*p.Loc("aperture"),
                         fmt::format("aperture \"{}\" is neither a built-in shape (gaussian, "
                                     "square, pentagon, star) nor an image (looked for {})",
                                     name, path));
    try {
        return ApertureShape::FromImage(path);
    } catch (const std::runtime_error &error) {
        throw ParseError(*p.Loc("aperture"), fmt::format("aperture \"{}\": {}", name, error.what()));
    }
}

// pbrt-v4's realistic camera: "lensfile", "aperturediameter" (mm), "focusdistance" (m) and
// "aperture", on a film of the Film's "diagonal".
RealisticCamera CreateRealisticCamera(const CameraSceneEntity &e, CameraMotion worldFromCamera,
                                      const RGBFilm &film, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    std::string lensFile = p.GetOneString("lensfile", "");
    if (lensFile.empty())
        throw ParseError(e.loc, "Camera \"realistic\" needs \"string lensfile\", a lens "
                                "description");
    const FileLoc &loc = *p.Loc("lensfile");
    std::string path = ResolvePath(folder, lensFile);
    std::string what = "lens file \"" + path + "\"";
    std::vector<LensElementInterface> lens = ReadLens(p, loc, path, what);
    Float focusDistance = p.GetOneFloat("focusdistance", 10);
    if (!(focusDistance > 0))
        throw ParseError(*p.Loc("focusdistance"),
                         fmt::format("\"focusdistance\" {} is not positive", focusDistance));
    std::optional<ApertureShape> aperture = CreateApertureShape(p, folder);
    p.ReportUnused();
    try {
        return RealisticCamera(std::move(worldFromCamera), film.FullResolution(), film.Diagonal(),
                               std::move(lens), focusDistance, std::move(aperture));
    } catch (const std::invalid_argument &error) {
        throw ParseError(loc, what + ": " + error.what());
    }
}

}  // namespace

Camera CreateCamera(const CameraSceneEntity &e, const RGBFilm &film, const std::string &folder) {
    const ParameterDictionary &p = e.parameters;
    ExposureTime(e);  // the film's imaging ratio uses it, and it is checked there
    CameraMotion worldFromCamera = CameraMotionOf(e);
    if (e.name == "spherical")
        return CreateSphericalCamera(e, std::move(worldFromCamera), film);
    if (e.name == "realistic")
        return CreateRealisticCamera(e, std::move(worldFromCamera), film, folder);
    if (!e.name.empty() && e.name != "perspective" && e.name != "orthographic")
        throw ParseError(e.loc, "unknown Camera \"" + e.name +
                                    "\": expected perspective, orthographic, spherical or "
                                    "realistic");
    Float lensRadius = p.GetOneFloat("lensradius", 0),
          focalDistance = p.GetOneFloat("focaldistance", 1e6f);
    Bounds2f window = ScreenWindow(p, film);
    if (e.name == "orthographic") {
        p.ReportUnused();
        return OrthographicCamera(worldFromCamera, film.FullResolution(), window, lensRadius,
                                  focalDistance);
    }
    Float fov = p.GetOneFloat("fov", 90);
    p.ReportUnused();
    return PerspectiveCamera(worldFromCamera, film.FullResolution(), window, fov, lensRadius,
                             focalDistance);
}

}  // namespace pbrt
