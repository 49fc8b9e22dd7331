// Typed access to a directive's parameter list (pbrt-v4's paramdict.h, reduced; host only).
//
// Lookups are by name; the type written in the file must be the one the caller asks for,
// otherwise it is a ParseError at the parameter ("float radius" read as an integer is a
// mistake in the file, not something to coerce silently). Every lookup marks the parameter
// used, and ReportUnused() turns the first parameter nobody read into an error, so a typo in a
// parameter name never goes unnoticed. Spectra stay descriptions (SpectrumParam): turning them
// into RGB is spectra.h's job.
#pragma once

#include "pbrt_ext/scene/parser.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/vecmath.h"

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pbrt {

class RGBColorSpace;

// How a parameter type's values are written and how many make one item (3 for a point3).
enum class ParameterValueKind { Number, Integer, Bool, String, Spectrum };

struct ParameterTypeInfo {
    std::string_view name;
    ParameterValueKind kind;
    int nPerItem;
};

// The canonical name of a type written in a file (resolving pbrt-v3/v4 aliases such as
// "point" and "color"), or the input unchanged when it is no alias.
std::string_view CanonicalParameterType(std::string_view type);
// The description of a canonical type name, or null for an unknown type.
const ParameterTypeInfo *LookupParameterType(std::string_view type);

// Throws ParseError unless the parameter has values and their number suits its type (a
// multiple of three for a point3); the parser calls it on every parameter it reads.
void CheckValueCount(const ParsedParameter &p);

// A spectrum as written in the file, before any conversion.
enum class SpectrumParamKind { RGB, Blackbody, Samples, Named, File };

struct SpectrumParam {
    SpectrumParamKind kind = SpectrumParamKind::RGB;
    // RGB: r, g, b. Blackbody: the temperature in kelvin. Samples: lambda0, value0,
    // lambda1, value1, ... with increasing wavelengths (nm). Empty for Named and File.
    std::vector<double> values;
    // Named: the spectrum's name ("metal-Au-eta"). File: the path as written (resolve it
    // against the directory of loc.filename).
    std::string name;
    FileLoc loc;

    std::string ToString() const;
};

class ParameterDictionary {
  public:
    ParameterDictionary() = default;
    explicit ParameterDictionary(ParsedParameterVector params);
    // `params` take precedence over `lowerPriority` (a shape's own parameters over those of
    // an `Attribute "shape"` directive), as in pbrt-v4.
    ParameterDictionary(ParsedParameterVector params, const ParsedParameterVector &lowerPriority);
    // `colorSpace`: the one in force at the directive (ColorSpace), in which its "rgb" values
    // are given, as pbrt-v4's ParameterDictionary carries it; null: sRGB.
    ParameterDictionary(ParsedParameterVector params, const ParsedParameterVector &lowerPriority,
                        const RGBColorSpace *colorSpace);

    // The colour space of the directive's "rgb" values (and, for a Film, its output's).
    const RGBColorSpace &ColorSpace() const;

    Float GetOneFloat(const std::string &name, Float def) const;
    int GetOneInt(const std::string &name, int def) const;
    bool GetOneBool(const std::string &name, bool def) const;
    std::string GetOneString(const std::string &name, const std::string &def) const;
    Point2f GetOnePoint2f(const std::string &name, Point2f def) const;
    Point3f GetOnePoint3f(const std::string &name, Point3f def) const;
    Vector3f GetOneVector3f(const std::string &name, Vector3f def) const;
    Normal3f GetOneNormal3f(const std::string &name, Normal3f def) const;

    // Arrays are empty when the parameter is absent.
    std::vector<Float> GetFloatArray(const std::string &name) const;
    std::vector<int> GetIntArray(const std::string &name) const;
    std::vector<Point2f> GetPoint2fArray(const std::string &name) const;
    std::vector<Point3f> GetPoint3fArray(const std::string &name) const;
    std::vector<Vector3f> GetVector3fArray(const std::string &name) const;
    std::vector<Normal3f> GetNormal3fArray(const std::string &name) const;
    std::vector<std::string> GetStringArray(const std::string &name) const;
    // "rgb" values three at a time (pbrt-v4's GetRGBArray: the rgbgrid medium's samples).
    std::vector<RGB> GetRGBArray(const std::string &name) const;

    // An "rgb", "blackbody" or "spectrum" parameter; nullopt when absent.
    std::optional<SpectrumParam> GetOneSpectrum(const std::string &name) const;
    // The texture name of a "texture" parameter, "" when absent. Parameters that may be a
    // texture or a value (pbrt-v4's "float"/"texture" and "rgb"/"texture" pairs) are
    // dispatched on ParameterType() first.
    std::string GetTexture(const std::string &name) const;

    bool HasParameter(const std::string &name) const { return find(name) != nullptr; }
    // The canonical type of the parameter `name`, "" when absent.
    std::string ParameterType(const std::string &name) const;
    // Where the parameter `name` was written, null when absent.
    const FileLoc *Loc(const std::string &name) const;

    // Throws ParseError "unused parameter \"type name\"" at the first-written parameter that
    // no lookup read and that no read parameter of the same name shadows.
    void ReportUnused() const;

    std::string ToString() const;

  private:
    const ParsedParameter *find(const std::string &name) const;
    const ParsedParameter *findTyped(const std::string &name, std::string_view type) const;
    template <typename T, typename Convert>
    std::vector<T> lookupArray(const std::string &name, std::string_view type,
                               Convert convert) const;
    template <typename T, typename Convert>
    T lookupSingle(const std::string &name, std::string_view type, T def,
                   Convert convert) const;

    // Highest priority first.
    ParsedParameterVector params;
    const RGBColorSpace *colorSpace = nullptr;  // null: sRGB
};

}  // namespace pbrt
