#include "pbrt_ext/scene/scenedescription.h"

#include "pbrt_ext/util/text.h"

#include <fmt/format.h>

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace pbrt {

namespace {

// The options pbrt-v4's scene files may set, and the type of each one's value.
struct KnownOption {
    const char *name, *type;
};
constexpr KnownOption knownOptions[] = {{"disablepixeljitter", "bool"},
                                        {"disabletexturefiltering", "bool"},
                                        {"disablewavelengthjitter", "bool"},
                                        {"displacementedgescale", "float"},
                                        {"forcediffuse", "bool"},
                                        {"msereferenceimage", "string"},
                                        {"msereferenceout", "string"},
                                        {"pixelstats", "bool"},
                                        {"rendercoordsys", "string"},
                                        {"seed", "integer"},
                                        {"wavefront", "bool"}};

std::string Unquote(const std::string &s) {
    if (s.size() >= 2 && s.front() == '"' && s.back() == '"') return s.substr(1, s.size() - 2);
    return s;
}

bool IsValidOptionValue(const std::string &type, const std::string &value) {
    const char *begin = value.data(), *end = value.data() + value.size();
    if (type == "bool") return value == "true" || value == "false";
    if (type == "integer") {
        int i;
        auto [ptr, ec] = std::from_chars(begin, end, i);
        return ec == std::errc() && ptr == end;
    }
    if (type == "float") {
        double d;
        auto [ptr, ec] = std::from_chars(begin, end, d);
        return ec == std::errc() && ptr == end && std::isfinite(d);
    }
    return true;  // string
}

std::string ExpectedOptionValue(const std::string &type) {
    if (type == "bool") return "true or false";
    return type == "integer" ? "an integer" : "a " + type;
}

std::string KnownOptionNames() {
    std::string names;
    for (const KnownOption &o : knownOptions)
        names += std::string(names.empty() ? "" : ", ") + o.name;
    return names;
}

}  // namespace

BasicSceneBuilder::BasicSceneBuilder(SceneDescription *scene, std::string inputName)
    : scene(scene), inputName(std::move(inputName)) {
    // pbrt-v4's defaults, so that a file naming none still describes a complete render.
    scene->camera.name = "perspective";
    scene->film.name = "rgb";
    scene->sampler.name = "zsobol";
    scene->filter.name = "gaussian";
    scene->integrator.name = "volpath";
    scene->accelerator.name = "bvh";
    scene->materials.push_back(SceneEntity("diffuse", ParameterDictionary(), FileLoc{}));
}

// ---- Checks and helpers -------------------------------------------------------------------

void BasicSceneBuilder::VerifyOptions(const char *directive, const FileLoc &loc) {
    if (currentBlock == BlockState::WorldBlock)
        throw ParseError(loc,
                         std::string("\"") + directive +
                             "\" is not allowed after WorldBegin; expected it before WorldBegin");
}

void BasicSceneBuilder::VerifyWorld(const char *directive, const FileLoc &loc) {
    if (currentBlock == BlockState::OptionsBlock)
        throw ParseError(loc,
                         std::string("\"") + directive +
                             "\" is not allowed before WorldBegin; expected it after WorldBegin");
}

template <typename F>
void BasicSceneBuilder::ForActiveTransforms(F f) {
    for (int i = 0; i < 2; ++i)
        if (graphicsState.activeTransformBits & (1 << i))
            graphicsState.ctm.t[i] = f(graphicsState.ctm.t[i]);
}

const Transform &BasicSceneBuilder::StaticCTM(const char *what, const FileLoc &loc) {
    if (graphicsState.ctm.IsAnimated() && FirstTime(std::string("moving ") + what))
        WarningAt(loc, "%s do not move over the shutter interval (as in pbrt-v4); the start "
                       "transform is used", what);
    return graphicsState.ctm.t[0];
}

static TransformSet Inverse(const TransformSet &s) { return {{Inverse(s.t[0]), Inverse(s.t[1])}}; }

bool BasicSceneBuilder::FirstTime(const std::string &topic) { return warned.insert(topic).second; }

// ---- Options ------------------------------------------------------------------------------

void BasicSceneBuilder::Option(const std::string &name, const std::string &value, FileLoc loc) {
    // The name may carry its type as parameters do ("bool disablepixeljitter").
    size_t space = name.find_last_of(' ');
    std::string declaredType = space == std::string::npos ? "" : name.substr(0, name.find(' '));
    std::string key =
        NormalizeOptionName(space == std::string::npos ? name : name.substr(space + 1));
    const KnownOption *option = nullptr;
    for (const KnownOption &o : knownOptions)
        if (key == o.name) option = &o;
    if (!option)
        throw ParseError(loc,
                         "unknown option \"" + name + "\"; expected one of " + KnownOptionNames());
    if (!declaredType.empty() && declaredType != option->type)
        throw ParseError(loc, "option \"" + key + "\" declared " + declaredType +
                                  "; expected type " + option->type);
    std::string v = Unquote(value);
    if (!IsValidOptionValue(option->type, v))
        throw ParseError(loc, "option \"" + key + "\": bad value \"" + v + "\"; expected " +
                                  ExpectedOptionValue(option->type));
    scene->options[key] = SceneOption{key, v, loc};
}

void BasicSceneBuilder::ColorSpace(const std::string &name, FileLoc loc) {
    const RGBColorSpace *cs = RGBColorSpace::GetNamed(name);
    if (!cs)
        throw ParseError(loc, "unknown color space \"" + name + "\"; expected one of " +
                                  RGBColorSpace::NamesList());
    graphicsState.colorSpace = cs;
}

void BasicSceneBuilder::PixelFilter(const std::string &name, ParsedParameterVector params,
                                    FileLoc loc) {
    VerifyOptions("PixelFilter", loc);
    scene->filter = SceneEntity(name, ParameterDictionary(std::move(params)), loc);
}

void BasicSceneBuilder::Film(const std::string &type, ParsedParameterVector params, FileLoc loc) {
    VerifyOptions("Film", loc);
    scene->film =
        SceneEntity(type, ParameterDictionary(std::move(params), {}, graphicsState.colorSpace), loc);
}

void BasicSceneBuilder::Sampler(const std::string &name, ParsedParameterVector params,
                                FileLoc loc) {
    VerifyOptions("Sampler", loc);
    scene->sampler = SceneEntity(name, ParameterDictionary(std::move(params)), loc);
}

void BasicSceneBuilder::Accelerator(const std::string &name, ParsedParameterVector params,
                                    FileLoc loc) {
    VerifyOptions("Accelerator", loc);
    scene->accelerator = SceneEntity(name, ParameterDictionary(std::move(params)), loc);
}

void BasicSceneBuilder::Integrator(const std::string &name, ParsedParameterVector params,
                                   FileLoc loc) {
    VerifyOptions("Integrator", loc);
    scene->integrator = SceneEntity(name, ParameterDictionary(std::move(params)), loc);
}

void BasicSceneBuilder::Camera(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    VerifyOptions("Camera", loc);
    scene->camera.name = name;
    scene->camera.parameters = ParameterDictionary(std::move(params), {}, graphicsState.colorSpace);
    scene->camera.loc = loc;
    scene->camera.cameraFromWorld = graphicsState.ctm;
    scene->camera.transformStartTime = scene->transformStartTime;
    scene->camera.transformEndTime = scene->transformEndTime;
    scene->camera.medium = graphicsState.outsideMedium;
    namedCoordinateSystems["camera"] = Inverse(graphicsState.ctm);
}

void BasicSceneBuilder::TransformTimes(Float start, Float end, FileLoc loc) {
    VerifyOptions("TransformTimes", loc);
    if (!(end >= start) || !IsFinite(start) || !IsFinite(end))
        throw ParseError(loc, fmt::format("TransformTimes {} {}: expected finite times with the "
                                          "end not before the start", start, end));
    scene->transformStartTime = start;
    scene->transformEndTime = end;
}

void BasicSceneBuilder::WorldBegin(FileLoc loc) {
    VerifyOptions("WorldBegin", loc);
    currentBlock = BlockState::WorldBlock;
    graphicsState.ctm = {};
    graphicsState.activeTransformBits = kAllTransforms;
    namedCoordinateSystems["world"] = {};
}

// ---- Transformations ----------------------------------------------------------------------

void BasicSceneBuilder::Identity(FileLoc) {
    ForActiveTransforms([](const class Transform &) { return pbrt::Transform(); });
}

void BasicSceneBuilder::Translate(Float dx, Float dy, Float dz, FileLoc) {
    ForActiveTransforms(
        [&](const class Transform &t) { return t * pbrt::Translate(Vector3f(dx, dy, dz)); });
}

void BasicSceneBuilder::Scale(Float sx, Float sy, Float sz, FileLoc) {
    ForActiveTransforms([&](const class Transform &t) { return t * pbrt::Scale(sx, sy, sz); });
}

void BasicSceneBuilder::Rotate(Float angle, Float ax, Float ay, Float az, FileLoc loc) {
    // A zero axis would fill the CTM with NaN, far from the directive that caused it.
    if (ax == 0 && ay == 0 && az == 0)
        throw ParseError(loc, "Rotate about the zero vector; expected a nonzero axis");
    ForActiveTransforms([&](const class Transform &t) {
        return t * pbrt::Rotate(angle, Vector3f(ax, ay, az));
    });
}

void BasicSceneBuilder::LookAt(Float ex, Float ey, Float ez, Float lx, Float ly, Float lz, Float ux,
                               Float uy, Float uz, FileLoc loc) {
    class Transform lookAt;
    try {
        lookAt = pbrt::LookAt(Point3f(ex, ey, ez), Point3f(lx, ly, lz), Vector3f(ux, uy, uz));
    } catch (const std::runtime_error &e) {
        throw ParseError(loc, e.what());
    }
    ForActiveTransforms([&](const class Transform &t) { return t * lookAt; });
}

// The file writes the matrix by columns (pbrt-v4): the 16 numbers are the transpose of m.
static Transform FromFileMatrix(const Float tr[16]) {
    SquareMatrix<4> m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) m[i][j] = tr[j * 4 + i];
    return Transform(m);
}

void BasicSceneBuilder::ConcatTransform(Float transform[16], FileLoc) {
    ForActiveTransforms([&](const class Transform &t) { return t * FromFileMatrix(transform); });
}

void BasicSceneBuilder::Transform(Float transform[16], FileLoc) {
    ForActiveTransforms([&](const class Transform &) { return FromFileMatrix(transform); });
}

void BasicSceneBuilder::CoordinateSystem(const std::string &name, FileLoc) {
    namedCoordinateSystems[name] = graphicsState.ctm;
}

void BasicSceneBuilder::CoordSysTransform(const std::string &name, FileLoc loc) {
    auto it = namedCoordinateSystems.find(name);
    if (it == namedCoordinateSystems.end())
        throw ParseError(loc, "unknown coordinate system \"" + name +
                                  "\"; expected \"camera\", \"world\" or a name given to "
                                  "CoordinateSystem before");
    graphicsState.ctm = it->second;  // both ends, whichever are active (pbrt-v4)
}

void BasicSceneBuilder::ActiveTransformAll(FileLoc) {
    graphicsState.activeTransformBits = kAllTransforms;
}

void BasicSceneBuilder::ActiveTransformStartTime(FileLoc) {
    graphicsState.activeTransformBits = 1;
}

void BasicSceneBuilder::ActiveTransformEndTime(FileLoc) { graphicsState.activeTransformBits = 2; }

// ---- Media --------------------------------------------------------------------------------

void BasicSceneBuilder::MakeNamedMedium(const std::string &name, ParsedParameterVector params,
                                        FileLoc loc) {
    if (auto it = scene->media.find(name); it != scene->media.end())
        throw ParseError(loc, "named medium \"" + name + "\" redefined; first defined at " +
                                  it->second.loc.ToString());
    scene->media[name] = TransformedSceneEntity(
        SceneEntity(name, ParameterDictionary(std::move(params), graphicsState.mediumAttributes,
                            graphicsState.colorSpace),
                    loc),
        StaticCTM("media", loc));
}

// Names are checked at EndOfFiles: pbrt-v4 lets MakeNamedMedium come after its use.
void BasicSceneBuilder::MediumInterface(const std::string &insideName,
                                        const std::string &outsideName, FileLoc loc) {
    graphicsState.insideMedium = insideName;
    graphicsState.outsideMedium = outsideName;
    mediumUses.push_back({insideName, loc});
    mediumUses.push_back({outsideName, loc});
}

// ---- Attributes and blocks ----------------------------------------------------------------

void BasicSceneBuilder::AttributeBegin(FileLoc loc) {
    VerifyWorld("AttributeBegin", loc);
    pushedGraphicsStates.push_back(graphicsState);
    pushStack.push_back({'a', loc});
}

void BasicSceneBuilder::AttributeEnd(FileLoc loc) {
    VerifyWorld("AttributeEnd", loc);
    PopBlock('a', loc);
}

// Closes the innermost block, which must be of the kind the closing directive names.
void BasicSceneBuilder::PopBlock(char kind, const FileLoc &loc) {
    const char *end = kind == 'a' ? "AttributeEnd" : "ObjectEnd";
    const char *begin = kind == 'a' ? "AttributeBegin" : "ObjectBegin";
    bool open = kind == 'a' ? !pushStack.empty() : !activeObject.empty();
    if (!open) throw ParseError(loc, std::string(end) + " without a matching " + begin);
    const OpenBlock &top = pushStack.back();
    if (top.kind != kind)
        throw ParseError(loc, std::string(end) + " inside the " +
                                  (top.kind == 'a' ? "AttributeBegin" : "ObjectBegin") + " at " +
                                  top.loc.ToString() + "; expected " +
                                  (top.kind == 'a' ? "AttributeEnd" : "ObjectEnd") + " first");
    graphicsState = std::move(pushedGraphicsStates.back());
    pushedGraphicsStates.pop_back();
    pushStack.pop_back();
    if (kind == 'o') activeObject.clear();
}

void BasicSceneBuilder::Attribute(const std::string &target, ParsedParameterVector params,
                                  FileLoc loc) {
    ParsedParameterVector *attributes = nullptr;
    if (target == "shape")
        attributes = &graphicsState.shapeAttributes;
    else if (target == "light")
        attributes = &graphicsState.lightAttributes;
    else if (target == "material")
        attributes = &graphicsState.materialAttributes;
    else if (target == "texture")
        attributes = &graphicsState.textureAttributes;
    else if (target == "medium")
        attributes = &graphicsState.mediumAttributes;
    else
        throw ParseError(loc, "unknown Attribute target \"" + target +
                                  "\"; expected \"shape\", \"light\", \"material\", \"medium\" "
                                  "or \"texture\"");
    // Attributes are defaults for the entities that follow, so they need not apply to each one
    // (pbrt-v4's mayBeUnused): they count as read. A later one replaces an earlier namesake.
    for (ParsedParameter &p : params) {
        p.lookedUp = true;
        bool replaced = false;
        for (ParsedParameter &a : *attributes)
            if (a.name == p.name) {
                a = p;
                replaced = true;
            }
        if (!replaced) attributes->push_back(std::move(p));
    }
}

void BasicSceneBuilder::ReverseOrientation(FileLoc loc) {
    VerifyWorld("ReverseOrientation", loc);
    graphicsState.reverseOrientation = !graphicsState.reverseOrientation;
}

// ---- Materials and textures ---------------------------------------------------------------

void BasicSceneBuilder::Texture(const std::string &name, const std::string &type,
                                const std::string &texname, ParsedParameterVector params,
                                FileLoc loc) {
    VerifyWorld("Texture", loc);
    if (type != "float" && type != "spectrum")
        throw ParseError(loc, "texture type \"" + type +
                                  "\" unknown; expected \"float\" or "
                                  "\"spectrum\"");
    auto &textures = type == "float" ? scene->floatTextures : scene->spectrumTextures;
    if (auto it = textures.find(name); it != textures.end())
        throw ParseError(loc, type + " texture \"" + name + "\" redefined; first defined at " +
                                  it->second.loc.ToString());
    textures[name] = TransformedSceneEntity(
        SceneEntity(texname,
                    ParameterDictionary(std::move(params), graphicsState.textureAttributes,
                            graphicsState.colorSpace), loc),
        StaticCTM("textures", loc));
}

void BasicSceneBuilder::Material(const std::string &name, ParsedParameterVector params,
                                 FileLoc loc) {
    VerifyWorld("Material", loc);
    scene->materials.push_back(SceneEntity(
        name, ParameterDictionary(std::move(params), graphicsState.materialAttributes,
                            graphicsState.colorSpace), loc));
    graphicsState.currentMaterialIndex = int(scene->materials.size()) - 1;
    graphicsState.currentMaterialName.clear();
}

void BasicSceneBuilder::MakeNamedMaterial(const std::string &name, ParsedParameterVector params,
                                          FileLoc loc) {
    VerifyWorld("MakeNamedMaterial", loc);
    if (auto it = scene->namedMaterials.find(name); it != scene->namedMaterials.end())
        throw ParseError(loc, "named material \"" + name + "\" redefined; first defined at " +
                                  it->second.loc.ToString());
    scene->namedMaterials[name] = SceneEntity(
        "", ParameterDictionary(std::move(params), graphicsState.materialAttributes,
                            graphicsState.colorSpace), loc);
}

void BasicSceneBuilder::NamedMaterial(const std::string &name, FileLoc loc) {
    // Checked at EndOfFiles: pbrt-v4 lets MakeNamedMaterial come after its use.
    VerifyWorld("NamedMaterial", loc);
    graphicsState.currentMaterialName = name;
    graphicsState.currentMaterialIndex = -1;
}

// ---- Lights and shapes --------------------------------------------------------------------

void BasicSceneBuilder::LightSource(const std::string &name, ParsedParameterVector params,
                                    FileLoc loc) {
    VerifyWorld("LightSource", loc);
    scene->lights.push_back(LightSceneEntity(
        TransformedSceneEntity(
            SceneEntity(name, ParameterDictionary(std::move(params), graphicsState.lightAttributes,
                            graphicsState.colorSpace),
                        loc),
            StaticCTM("lights", loc)),
        graphicsState.outsideMedium));
}

void BasicSceneBuilder::AreaLightSource(const std::string &name, ParsedParameterVector params,
                                        FileLoc loc) {
    VerifyWorld("AreaLightSource", loc);
    graphicsState.areaLight = SceneEntity(
        name, ParameterDictionary(std::move(params), graphicsState.lightAttributes,
                            graphicsState.colorSpace), loc);
}

void BasicSceneBuilder::Shape(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    VerifyWorld("Shape", loc);
    if (!activeObject.empty() && graphicsState.areaLight && FirstTime("arealight-in-object"))
        WarningAt(loc,
                  "area lights are not supported inside ObjectBegin; instances of object "
                  "\"%s\" will not emit",
                  activeObject.c_str());
    ShapeSceneEntity shape;
    static_cast<SceneEntity &>(shape) = SceneEntity(
        name, ParameterDictionary(std::move(params), graphicsState.shapeAttributes,
                            graphicsState.colorSpace), loc);
    shape.worldFromObject = graphicsState.ctm.t[0];
    shape.worldFromObjectEnd = graphicsState.ctm.t[1];
    shape.reverseOrientation = graphicsState.reverseOrientation;
    shape.materialIndex = graphicsState.currentMaterialIndex;
    shape.materialName = graphicsState.currentMaterialName;
    shape.areaLight = graphicsState.areaLight;
    shape.insideObject = activeObject;
    shape.insideMedium = graphicsState.insideMedium;
    shape.outsideMedium = graphicsState.outsideMedium;
    if (shape.IsAnimated() && shape.areaLight) {
        if (FirstTime("moving area light"))
            WarningAt(loc, "moving shapes do not emit (area lights on animated shapes are not "
                           "supported, as in pbrt-v4); the emission is ignored");
        shape.areaLight.reset();
    }
    if (!activeObject.empty())
        scene->instanceDefinitions[activeObject].shapeIndices.push_back(int(scene->shapes.size()));
    scene->shapes.push_back(std::move(shape));
}

// ---- Object instancing --------------------------------------------------------------------

void BasicSceneBuilder::ObjectBegin(const std::string &name, FileLoc loc) {
    VerifyWorld("ObjectBegin", loc);
    if (!activeObject.empty())
        throw ParseError(loc, "ObjectBegin \"" + name + "\" inside ObjectBegin \"" + activeObject +
                                  "\" at " + pushStack.back().loc.ToString() +
                                  "; expected ObjectEnd first (objects do not nest)");
    if (auto it = scene->instanceDefinitions.find(name); it != scene->instanceDefinitions.end())
        throw ParseError(loc, "object \"" + name + "\" redefined; first defined at " +
                                  it->second.loc.ToString());
    pushedGraphicsStates.push_back(graphicsState);
    pushStack.push_back({'o', loc});
    activeObject = name;
    scene->instanceDefinitions[name] = InstanceDefinitionSceneEntity{name, loc, {}};
}

void BasicSceneBuilder::ObjectEnd(FileLoc loc) {
    VerifyWorld("ObjectEnd", loc);
    PopBlock('o', loc);
}

void BasicSceneBuilder::ObjectInstance(const std::string &name, FileLoc loc) {
    // The object itself may be defined later in the file: checked at EndOfFiles.
    VerifyWorld("ObjectInstance", loc);
    if (!activeObject.empty())
        throw ParseError(loc, "ObjectInstance \"" + name + "\" inside ObjectBegin \"" +
                                  activeObject +
                                  "\"; expected ObjectInstance outside object "
                                  "definitions");
    scene->instances.push_back(InstanceSceneEntity{name, loc, graphicsState.ctm});
}

// ---- End of input -------------------------------------------------------------------------

void BasicSceneBuilder::EndOfFiles() {
    if (currentBlock != BlockState::WorldBlock)
        throw ParseError(FileLoc{inputName, 0, 0},
                         "end of input before WorldBegin; expected WorldBegin and the scene");
    if (!pushStack.empty()) {
        const OpenBlock &open = pushStack.back();
        throw ParseError(open.loc, open.kind == 'a'
                                       ? "AttributeBegin without a matching AttributeEnd"
                                       : "ObjectBegin without a matching ObjectEnd");
    }
    CheckReferences();
}

void BasicSceneBuilder::CheckReferences() const {
    for (const ShapeSceneEntity &shape : scene->shapes)
        if (shape.materialIndex < 0 && !scene->namedMaterials.count(shape.materialName))
            throw ParseError(shape.loc, "named material \"" + shape.materialName +
                                            "\" is not defined; expected MakeNamedMaterial \"" +
                                            shape.materialName + "\" in the scene");
    for (const auto &[name, loc] : mediumUses)
        if (!name.empty() && !scene->media.count(name))
            throw ParseError(loc, "medium \"" + name +
                                      "\" is not defined; expected MakeNamedMedium \"" + name +
                                      "\" in the scene");
    for (const InstanceSceneEntity &instance : scene->instances)
        if (!scene->instanceDefinitions.count(instance.name))
            throw ParseError(instance.loc, "object \"" + instance.name +
                                               "\" is not defined; expected ObjectBegin \"" +
                                               instance.name + "\" in the scene");
}

SceneDescription DescribeSceneFile(const std::string &filename) {
    SceneDescription scene;
    BasicSceneBuilder builder(&scene, filename);
    ParseFile(&builder, filename);
    return scene;
}

SceneDescription DescribeSceneFiles(const std::vector<SceneFile> &files) {
    SceneDescription scene;
    BasicSceneBuilder builder(&scene, files.empty() ? "<input>" : files.front().filename);
    ParseFiles(&builder, files);
    return scene;
}

SceneDescription DescribeSceneString(std::string text, std::string name) {
    SceneDescription scene;
    BasicSceneBuilder builder(&scene, name);
    ParseString(&builder, std::move(text), std::move(name));
    return scene;
}

}  // namespace pbrt
