#include "pbrt_ext/scene/paramdict.h"

#include "pbrt_ext/spectra/colorspace.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <set>
#include <utility>

namespace pbrt {

namespace {

constexpr std::array<ParameterTypeInfo, 13> kParameterTypes = {{
    {"integer", ParameterValueKind::Integer, 1},
    {"float", ParameterValueKind::Number, 1},
    {"point2", ParameterValueKind::Number, 2},
    {"vector2", ParameterValueKind::Number, 2},
    {"point3", ParameterValueKind::Number, 3},
    {"vector3", ParameterValueKind::Number, 3},
    {"normal", ParameterValueKind::Number, 3},
    {"rgb", ParameterValueKind::Number, 3},
    {"blackbody", ParameterValueKind::Number, 1},
    // (lambda, value) pairs; a spectrum given by name or file has one string instead.
    {"spectrum", ParameterValueKind::Spectrum, 2},
    {"bool", ParameterValueKind::Bool, 1},
    {"string", ParameterValueKind::String, 1},
    {"texture", ParameterValueKind::String, 1},
}};

// pbrt-v3 spellings and pbrt-v4's own synonyms.
constexpr std::array<std::pair<std::string_view, std::string_view>, 4> kTypeAliases = {{
    {"point", "point3"}, {"vector", "vector3"}, {"normal3", "normal"}, {"color", "rgb"}}};

std::string Quoted(const ParsedParameter &p) { return "\"" + p.type + " " + p.name + "\""; }

size_t ValueCount(const ParsedParameter &p) {
    return p.numbers.size() + p.strings.size() + p.bools.size();
}

[[noreturn]] void ThrowCount(const ParsedParameter &p, const std::string &expected) {
    size_t n = ValueCount(p);
    throw ParseError(p.loc, Quoted(p) + " has " + std::to_string(n) +
                                (n == 1 ? " value" : " values") + ": expected " + expected);
}

void CheckExactly(const ParsedParameter &p, size_t n) {
    if (ValueCount(p) != n)
        ThrowCount(p, n == 1 ? std::string("one") : std::to_string(n));
}

void CheckMultipleOf(const ParsedParameter &p, size_t n) {
    if (ValueCount(p) == 0)
        ThrowCount(p, "at least one");
    if (ValueCount(p) % n != 0)
        ThrowCount(p, "a multiple of " + std::to_string(n));
}

std::string FormatNumber(double v) {
    char buf[32];
    auto result = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, result.ptr);
}

// pbrt-v4 tries the named spectra first and then a file; no named spectrum contains a path
// separator or a dot, so the string alone tells which it is.
bool IsSpectrumFile(const std::string &s) {
    return s.find_first_of("./\\") != std::string::npos;
}

void CheckIncreasingWavelengths(const ParsedParameter &p) {
    for (size_t i = 2; i < p.numbers.size(); i += 2)
        if (p.numbers[i] <= p.numbers[i - 2])
            throw ParseError(p.loc, Quoted(p) + ": wavelength " + FormatNumber(p.numbers[i]) +
                                        " follows " + FormatNumber(p.numbers[i - 2]) +
                                        ": expected increasing wavelengths");
}

}  // namespace

void CheckValueCount(const ParsedParameter &p) {
    // A spectrum's name or file is one string; its numbers come in (lambda, value) pairs.
    const ParameterTypeInfo *info = LookupParameterType(p.type);
    CheckMultipleOf(p, info && p.strings.empty() ? info->nPerItem : 1);
}

std::string_view CanonicalParameterType(std::string_view type) {
    for (const auto &[alias, canonical] : kTypeAliases)
        if (type == alias)
            return canonical;
    return type;
}

const ParameterTypeInfo *LookupParameterType(std::string_view type) {
    for (const ParameterTypeInfo &info : kParameterTypes)
        if (info.name == type)
            return &info;
    return nullptr;
}

std::string SpectrumParam::ToString() const {
    static constexpr const char *kKindNames[] = {"rgb", "blackbody", "samples", "named", "file"};
    std::string s = std::string("[ SpectrumParam kind: ") + kKindNames[int(kind)] + " values: [";
    for (double v : values)
        s += " " + FormatNumber(v);
    return s + " ] name: \"" + name + "\" loc: " + loc.ToString() + " ]";
}

ParameterDictionary::ParameterDictionary(ParsedParameterVector p)
    : ParameterDictionary(std::move(p), {}) {}

ParameterDictionary::ParameterDictionary(ParsedParameterVector p,
                                         const ParsedParameterVector &lowerPriority)
    : ParameterDictionary(std::move(p), lowerPriority, nullptr) {}

ParameterDictionary::ParameterDictionary(ParsedParameterVector p,
                                         const ParsedParameterVector &lowerPriority,
                                         const RGBColorSpace *colorSpace)
    : params(std::move(p)), colorSpace(colorSpace) {
    // The last of two equal names in one list wins, as in pbrt-v4: reversing puts it first.
    std::reverse(params.begin(), params.end());
    params.insert(params.end(), lowerPriority.rbegin(), lowerPriority.rend());
}

const RGBColorSpace &ParameterDictionary::ColorSpace() const {
    return colorSpace ? *colorSpace : RGBColorSpace::sRGB();
}

const ParsedParameter *ParameterDictionary::find(const std::string &name) const {
    for (const ParsedParameter &p : params)
        if (p.name == name)
            return &p;
    return nullptr;
}

const ParsedParameter *ParameterDictionary::findTyped(const std::string &name,
                                                      std::string_view type) const {
    const ParsedParameter *p = find(name);
    if (p && p->type != type)
        throw ParseError(p->loc, "parameter " + Quoted(*p) + " has the wrong type: expected \"" +
                                     std::string(type) + " " + name + "\"");
    return p;
}

template <typename T, typename Convert>
T ParameterDictionary::lookupSingle(const std::string &name, std::string_view type, T def,
                                    Convert convert) const {
    const ParsedParameter *p = findTyped(name, type);
    if (!p)
        return def;
    CheckExactly(*p, LookupParameterType(type)->nPerItem);
    p->lookedUp = true;
    return convert(*p, 0);
}

template <typename T, typename Convert>
std::vector<T> ParameterDictionary::lookupArray(const std::string &name, std::string_view type,
                                                Convert convert) const {
    const ParsedParameter *p = findTyped(name, type);
    if (!p)
        return {};
    int nPerItem = LookupParameterType(type)->nPerItem;
    CheckMultipleOf(*p, nPerItem);
    p->lookedUp = true;
    std::vector<T> values;
    for (size_t i = 0; i < ValueCount(*p) / nPerItem; ++i)
        values.push_back(convert(*p, i));
    return values;
}

namespace {
// Item i of a parameter as each C++ type; counts are checked before these are called.
Float AsFloat(const ParsedParameter &p, size_t i) { return Float(p.numbers[i]); }
int AsInt(const ParsedParameter &p, size_t i) { return int(p.numbers[i]); }
bool AsBool(const ParsedParameter &p, size_t i) { return p.bools[i] != 0; }
std::string AsString(const ParsedParameter &p, size_t i) { return p.strings[i]; }
Point2f AsPoint2f(const ParsedParameter &p, size_t i) {
    return Point2f(Float(p.numbers[2 * i]), Float(p.numbers[2 * i + 1]));
}
template <typename T>
T AsTriple(const ParsedParameter &p, size_t i) {
    return T(Float(p.numbers[3 * i]), Float(p.numbers[3 * i + 1]), Float(p.numbers[3 * i + 2]));
}
}  // namespace

Float ParameterDictionary::GetOneFloat(const std::string &name, Float def) const {
    return lookupSingle(name, "float", def, AsFloat);
}

int ParameterDictionary::GetOneInt(const std::string &name, int def) const {
    return lookupSingle(name, "integer", def, AsInt);
}

bool ParameterDictionary::GetOneBool(const std::string &name, bool def) const {
    return lookupSingle(name, "bool", def, AsBool);
}

std::string ParameterDictionary::GetOneString(const std::string &name,
                                              const std::string &def) const {
    return lookupSingle(name, "string", def, AsString);
}

Point2f ParameterDictionary::GetOnePoint2f(const std::string &name, Point2f def) const {
    return lookupSingle(name, "point2", def, AsPoint2f);
}

Point3f ParameterDictionary::GetOnePoint3f(const std::string &name, Point3f def) const {
    return lookupSingle(name, "point3", def, AsTriple<Point3f>);
}

Vector3f ParameterDictionary::GetOneVector3f(const std::string &name, Vector3f def) const {
    return lookupSingle(name, "vector3", def, AsTriple<Vector3f>);
}

Normal3f ParameterDictionary::GetOneNormal3f(const std::string &name, Normal3f def) const {
    return lookupSingle(name, "normal", def, AsTriple<Normal3f>);
}

std::vector<Float> ParameterDictionary::GetFloatArray(const std::string &name) const {
    return lookupArray<Float>(name, "float", AsFloat);
}

std::vector<int> ParameterDictionary::GetIntArray(const std::string &name) const {
    return lookupArray<int>(name, "integer", AsInt);
}

std::vector<Point2f> ParameterDictionary::GetPoint2fArray(const std::string &name) const {
    return lookupArray<Point2f>(name, "point2", AsPoint2f);
}

std::vector<Point3f> ParameterDictionary::GetPoint3fArray(const std::string &name) const {
    return lookupArray<Point3f>(name, "point3", AsTriple<Point3f>);
}

std::vector<Vector3f> ParameterDictionary::GetVector3fArray(const std::string &name) const {
    return lookupArray<Vector3f>(name, "vector3", AsTriple<Vector3f>);
}

std::vector<Normal3f> ParameterDictionary::GetNormal3fArray(const std::string &name) const {
    return lookupArray<Normal3f>(name, "normal", AsTriple<Normal3f>);
}

std::vector<std::string> ParameterDictionary::GetStringArray(const std::string &name) const {
    return lookupArray<std::string>(name, "string", AsString);
}

std::vector<RGB> ParameterDictionary::GetRGBArray(const std::string &name) const {
    return lookupArray<RGB>(name, "rgb", AsTriple<RGB>);
}

std::optional<SpectrumParam> ParameterDictionary::GetOneSpectrum(const std::string &name) const {
    const ParsedParameter *p = find(name);
    if (!p)
        return {};
    SpectrumParam s;
    s.loc = p->loc;
    if (p->type == "rgb") {
        CheckExactly(*p, 3);
        s.kind = SpectrumParamKind::RGB;
    } else if (p->type == "blackbody") {
        CheckExactly(*p, 1);
        s.kind = SpectrumParamKind::Blackbody;
    } else if (p->type == "spectrum" && !p->strings.empty()) {
        CheckExactly(*p, 1);
        s.kind = IsSpectrumFile(p->strings[0]) ? SpectrumParamKind::File
                                               : SpectrumParamKind::Named;
        s.name = p->strings[0];
    } else if (p->type == "spectrum") {
        CheckMultipleOf(*p, 2);
        CheckIncreasingWavelengths(*p);
        s.kind = SpectrumParamKind::Samples;
    } else {
        throw ParseError(p->loc, "parameter " + Quoted(*p) +
                                     " has the wrong type: expected \"rgb " + name +
                                     "\", \"spectrum " + name + "\" or \"blackbody " + name +
                                     "\"");
    }
    s.values = p->numbers;
    p->lookedUp = true;
    return s;
}

std::string ParameterDictionary::GetTexture(const std::string &name) const {
    const ParsedParameter *p = findTyped(name, "texture");
    if (!p)
        return "";
    CheckExactly(*p, 1);
    p->lookedUp = true;
    return p->strings[0];
}

std::string ParameterDictionary::ParameterType(const std::string &name) const {
    const ParsedParameter *p = find(name);
    return p ? p->type : "";
}

const FileLoc *ParameterDictionary::Loc(const std::string &name) const {
    const ParsedParameter *p = find(name);
    return p ? &p->loc : nullptr;
}

void ParameterDictionary::ReportUnused() const {
    // Lookups read the highest-priority parameter of a name, so lower-priority ones of a name
    // that was read are shadowed, not unused. params run in reverse file order, so the last
    // unused one is the one written first.
    std::set<std::string> used;
    const ParsedParameter *unused = nullptr;
    for (const ParsedParameter &p : params) {
        if (p.lookedUp)
            used.insert(p.name);
        else if (!used.count(p.name))
            unused = &p;
    }
    if (unused)
        throw ParseError(unused->loc, "unused parameter " + Quoted(*unused));
}

std::string ParameterDictionary::ToString() const {
    std::string s = "[ ParameterDictionary params: ";
    for (const ParsedParameter &p : params)
        s += p.ToString() + " ";
    return s + "]";
}

}  // namespace pbrt
