// The scene as the file describes it: pbrt-v4's BasicSceneBuilder (the ParserTarget that tracks
// the graphics state) and the entities of its BasicScene, with render space = world space.
//
// Everything here is plain data: names, unevaluated ParameterDictionary objects and the FileLoc
// of the directive that made each entity, so that the conversion to a SceneBuilder (which
// creates only what is referenced) can report errors where the user wrote them. Nothing is
// loaded, nothing is checked against what a shape or material accepts; that is the converter's.
#pragma once

#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "pbrt_ext/scene/paramdict.h"
#include "pbrt_ext/scene/parser.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/transform.h"

namespace pbrt {

// A directive's type name ("perspective", "trianglemesh", "diffuse", ...), its parameters and
// where it was written.
struct SceneEntity {
    SceneEntity() = default;
    SceneEntity(std::string name, ParameterDictionary parameters, FileLoc loc)
        : name(std::move(name)), parameters(std::move(parameters)), loc(std::move(loc)) {}

    std::string name;
    ParameterDictionary parameters;
    FileLoc loc;
};

// Lights and textures: placed by the CTM in force at their directive.
struct TransformedSceneEntity : SceneEntity {
    TransformedSceneEntity() = default;
    TransformedSceneEntity(SceneEntity entity, const Transform &worldFromObject)
        : SceneEntity(std::move(entity)), worldFromObject(worldFromObject) {}

    Transform worldFromObject;
};

// A light source: the medium in force at its directive is the one it is in.
struct LightSceneEntity : TransformedSceneEntity {
    LightSceneEntity() = default;
    LightSceneEntity(TransformedSceneEntity entity, std::string medium)
        : TransformedSceneEntity(std::move(entity)), medium(std::move(medium)) {}

    std::string medium;  // empty: vacuum
};

// The CTM at the start and the end of the shutter interval (pbrt-v4's TransformSet): the two
// differ for what moves.
struct TransformSet {
    Transform t[2];
    bool IsAnimated() const { return !(t[0] == t[1]); }
};

struct CameraSceneEntity : SceneEntity {
    TransformSet cameraFromWorld;
    Float transformStartTime = 0, transformEndTime = 1;  // the TransformTimes before Camera
    std::string medium;  // the outside medium in force at Camera; empty: vacuum
};

struct ShapeSceneEntity : SceneEntity {
    Transform worldFromObject;  // at the start of the shutter interval
    Transform worldFromObjectEnd;
    bool IsAnimated() const { return !(worldFromObject == worldFromObjectEnd); }
    bool reverseOrientation = false;
    // The material in force: an index into SceneDescription::materials, or -1 and the name of a
    // named material (pbrt-v4's pair; whichever of Material and NamedMaterial came last wins).
    int materialIndex = 0;
    std::string materialName;
    // The AreaLightSource in force, if any (name "diffuse" and its parameters).
    std::optional<SceneEntity> areaLight;
    // The ObjectBegin this shape was defined in; empty for shapes placed in the world directly.
    std::string insideObject;
    // The MediumInterface in force: named media inside and outside, empty for vacuum.
    std::string insideMedium, outsideMedium;
};

// An ObjectBegin/ObjectEnd block: the shapes it defines, as indices into SceneDescription::shapes.
struct InstanceDefinitionSceneEntity {
    std::string name;
    FileLoc loc;
    std::vector<int> shapeIndices;
};

struct InstanceSceneEntity {
    std::string name;  // the object placed
    FileLoc loc;
    TransformSet worldFromInstance;
};

// An `Option "type name" value` directive; the value is validated for the option's type and kept
// as text without quotes ("true", "12", "ref.exr").
struct SceneOption {
    std::string name, value;
    FileLoc loc;
};

struct SceneDescription {
    // Options (before WorldBegin); pbrt-v4's defaults when the file does not name one.
    CameraSceneEntity camera;
    SceneEntity film, sampler, integrator, filter, accelerator;
    std::map<std::string, SceneOption> options;  // by pbrt-v4's normalized option name
    // TransformTimes: the times of the CTM's two ends.
    Float transformStartTime = 0, transformEndTime = 1;

    // The world. Shapes inside object definitions are listed too (insideObject set); only
    // instances place them.
    std::vector<ShapeSceneEntity> shapes;
    std::vector<LightSceneEntity> lights;
    // Anonymous materials in the order of their Material directives; materials[0] is pbrt-v4's
    // default "diffuse", the material of shapes before any Material directive.
    std::vector<SceneEntity> materials;
    // MakeNamedMaterial: entity name empty, the type in its "string type" parameter (pbrt-v4).
    std::map<std::string, SceneEntity> namedMaterials;
    // Texture "name" "float"|"spectrum" "class": keyed by name, entity name = the class.
    std::map<std::string, TransformedSceneEntity> floatTextures, spectrumTextures;
    std::map<std::string, InstanceDefinitionSceneEntity> instanceDefinitions;
    std::vector<InstanceSceneEntity> instances;
    // MakeNamedMedium, by name: entity name = the medium's name, its type in "string type",
    // placed by the CTM at the directive.
    std::map<std::string, TransformedSceneEntity> media;
};

// Turns parser callbacks into a SceneDescription. Violations of the file's structure throw
// ParseError at the offending directive; unsupported features warn once (WarningAt) and are
// skipped. EndOfFiles() checks what only the whole file can tell: a WorldBegin, closed blocks,
// defined named materials and objects.
class BasicSceneBuilder : public ParserTarget {
  public:
    // inputName (the main scene file) locates the errors that no directive has, such as a
    // missing WorldBegin.
    explicit BasicSceneBuilder(SceneDescription *scene, std::string inputName = "<input>");

    void Option(const std::string &name, const std::string &value, FileLoc loc) override;
    void Identity(FileLoc loc) override;
    void Translate(Float dx, Float dy, Float dz, FileLoc loc) override;
    void Scale(Float sx, Float sy, Float sz, FileLoc loc) override;
    void Rotate(Float angle, Float ax, Float ay, Float az, FileLoc loc) override;
    void LookAt(Float ex, Float ey, Float ez, Float lx, Float ly, Float lz, Float ux, Float uy,
                Float uz, FileLoc loc) override;
    void ConcatTransform(Float transform[16], FileLoc loc) override;
    void Transform(Float transform[16], FileLoc loc) override;
    void CoordinateSystem(const std::string &name, FileLoc loc) override;
    void CoordSysTransform(const std::string &name, FileLoc loc) override;
    void ActiveTransformAll(FileLoc loc) override;
    void ActiveTransformEndTime(FileLoc loc) override;
    void ActiveTransformStartTime(FileLoc loc) override;
    void TransformTimes(Float start, Float end, FileLoc loc) override;
    void ColorSpace(const std::string &name, FileLoc loc) override;
    void PixelFilter(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void Film(const std::string &type, ParsedParameterVector params, FileLoc loc) override;
    void Sampler(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void Accelerator(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void Integrator(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void Camera(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void MakeNamedMedium(const std::string &name, ParsedParameterVector params,
                         FileLoc loc) override;
    void MediumInterface(const std::string &insideName, const std::string &outsideName,
                         FileLoc loc) override;
    void WorldBegin(FileLoc loc) override;
    void AttributeBegin(FileLoc loc) override;
    void AttributeEnd(FileLoc loc) override;
    void Attribute(const std::string &target, ParsedParameterVector params, FileLoc loc) override;
    void Texture(const std::string &name, const std::string &type, const std::string &texname,
                 ParsedParameterVector params, FileLoc loc) override;
    void Material(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void MakeNamedMaterial(const std::string &name, ParsedParameterVector params,
                           FileLoc loc) override;
    void NamedMaterial(const std::string &name, FileLoc loc) override;
    void LightSource(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void AreaLightSource(const std::string &name, ParsedParameterVector params,
                         FileLoc loc) override;
    void Shape(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void ReverseOrientation(FileLoc loc) override;
    void ObjectBegin(const std::string &name, FileLoc loc) override;
    void ObjectEnd(FileLoc loc) override;
    void ObjectInstance(const std::string &name, FileLoc loc) override;
    void EndOfFiles() override;

  private:
    // What AttributeBegin saves and AttributeEnd restores.
    struct GraphicsState {
        TransformSet ctm;
        // Which of ctm's two ends the transformation directives change (ActiveTransform): bit
        // 0 the start, bit 1 the end.
        int activeTransformBits = kAllTransforms;
        bool reverseOrientation = false;
        int currentMaterialIndex = 0;
        std::string currentMaterialName;
        std::optional<SceneEntity> areaLight;
        std::string insideMedium, outsideMedium;  // MediumInterface; empty: vacuum
        // ColorSpace: the space of later directives' "rgb" values (and of the Film's output).
        const RGBColorSpace *colorSpace = &RGBColorSpace::sRGB();
        // Attribute "shape"|"light"|"material"|"medium"|"texture": defaults for later
        // directives.
        ParsedParameterVector shapeAttributes, lightAttributes, materialAttributes,
            mediumAttributes, textureAttributes;
    };
    static constexpr int kAllTransforms = 3;
    enum class BlockState { OptionsBlock, WorldBlock };
    // An open AttributeBegin ('a') or ObjectBegin ('o') and where it was opened.
    struct OpenBlock {
        char kind;
        FileLoc loc;
    };

    void VerifyOptions(const char *directive, const FileLoc &loc);
    void VerifyWorld(const char *directive, const FileLoc &loc);
    // Replaces each active end t of the CTM with f(t).
    template <typename F>
    void ForActiveTransforms(F f);
    // The start of the CTM for what pbrt-v4 does not move (lights, textures, media), with a
    // warning, once per kind, where the CTM moves.
    const class Transform &StaticCTM(const char *what, const FileLoc &loc);
    void PopBlock(char kind, const FileLoc &loc);
    bool FirstTime(const std::string &topic);
    void CheckReferences() const;

    SceneDescription *scene;
    BlockState currentBlock = BlockState::OptionsBlock;
    GraphicsState graphicsState;
    std::vector<GraphicsState> pushedGraphicsStates;
    std::vector<OpenBlock> pushStack;
    std::map<std::string, TransformSet> namedCoordinateSystems;
    std::string activeObject;  // the ObjectBegin being defined, empty outside one
    // Every medium name a MediumInterface directive used, and where: checked at EndOfFiles.
    std::vector<std::pair<std::string, FileLoc>> mediumUses;
    std::string inputName;
    std::set<std::string> warned;
};

// The description of a scene file or text: ParseFile/ParseString into a BasicSceneBuilder.
SceneDescription DescribeSceneFile(const std::string &filename);
SceneDescription DescribeSceneString(std::string text, std::string name = "<string>");
// Several files in order, as one scene.
SceneDescription DescribeSceneFiles(const std::vector<SceneFile> &files);

}  // namespace pbrt
