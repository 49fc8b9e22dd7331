// pbrt-v4's --format and --toply: a scene's directives printed back in pbrt-v4's syntax, one
// directive a line, attribute and object blocks indented, Includes inlined (the parser follows
// them), numbers in their shortest exact form, so that the printed scene is the same scene.
// --toply also writes each "trianglemesh" to a binary PLY file and prints a "plymesh" naming it;
// --upgrade rewrites pbrt-v3's directives as pbrt-v4's on the way (scene/upgrade.h).
#pragma once

#include "pbrt_ext/scene/parser.h"

#include <optional>
#include <ostream>
#include <string>

namespace pbrt {

class FormattingTarget final : public ParserTarget {
  public:
    // plyFolder: where --toply writes mesh_00001.ply, ...; none: meshes stay inline. upgrade:
    // pbrt-v3's directives are rewritten as pbrt-v4's (--upgrade, scene/upgrade.h).
    FormattingTarget(std::ostream &out, std::optional<std::string> plyFolder = std::nullopt,
                     bool upgrade = false)
        : out(out), plyFolder(std::move(plyFolder)), upgrade(upgrade) {}

    void Scale(Float sx, Float sy, Float sz, FileLoc loc) override;
    void Shape(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void Option(const std::string &name, const std::string &value, FileLoc loc) override;
    void Identity(FileLoc loc) override;
    void Translate(Float dx, Float dy, Float dz, FileLoc loc) override;
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
    void MakeNamedMedium(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void MediumInterface(const std::string &insideName, const std::string &outsideName,
                         FileLoc loc) override;
    void WorldBegin(FileLoc loc) override;
    void AttributeBegin(FileLoc loc) override;
    void AttributeEnd(FileLoc loc) override;
    void Attribute(const std::string &target, ParsedParameterVector params, FileLoc loc) override;
    void Texture(const std::string &name, const std::string &type, const std::string &texname,
                 ParsedParameterVector params, FileLoc loc) override;
    void Material(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void MakeNamedMaterial(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void NamedMaterial(const std::string &name, FileLoc loc) override;
    void LightSource(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void AreaLightSource(const std::string &name, ParsedParameterVector params, FileLoc loc) override;
    void ReverseOrientation(FileLoc loc) override;
    void ObjectBegin(const std::string &name, FileLoc loc) override;
    void ObjectEnd(FileLoc loc) override;
    void ObjectInstance(const std::string &name, FileLoc loc) override;
    void EndOfFiles() override;

  private:
    // One directive: its words (already quoted where they are strings), then its parameters.
    void Line(const std::string &words, const ParsedParameterVector &params = {});
    // A directive naming its type (Film "rgb", Material "diffuse", ...), upgraded by rule first
    // under --upgrade.
    using UpgradeRule = void (*)(std::string &, ParsedParameterVector &, const FileLoc &);
    void Entity(const char *directive, std::string name, ParsedParameterVector &params,
                const FileLoc &loc, UpgradeRule rule);
    // --toply: the PLY file's name, or none to print the mesh inline (one with faceIndices).
    std::optional<std::string> WritePLY(const ParsedParameterVector &params, const FileLoc &loc);

    std::ostream &out;
    std::optional<std::string> plyFolder;
    bool upgrade;
    int indent = 0;
    int meshes = 0;
};

// "text" with pbrt-v4's escapes.
std::string QuotedString(const std::string &text);

}  // namespace pbrt
