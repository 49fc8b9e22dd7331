#include "pbrt_ext/scene/formatter.h"

#include "pbrt_ext/scene/upgrade.h"

#include "pbrt_ext/util/atomicfile.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/text.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace pbrt {

namespace {

// The shortest text that parses back to v exactly.
template <typename T>
std::string Number(T v) {
    char buf[32];
    auto result = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, result.ptr);
}

std::string Numbers(std::initializer_list<Float> values) {
    std::string s;
    for (Float v : values) s += (s.empty() ? "" : " ") + Number(v);
    return s;
}

std::string Matrix(const Float m[16]) {
    std::string s = "[";
    for (int i = 0; i < 16; ++i) s += " " + Number(m[i]);
    return s + " ]";
}

std::string Parameter(const ParsedParameter &p) {
    std::string s = QuotedString(p.type + " " + p.name) + " [";
    for (double v : p.numbers) s += " " + Number(v);
    for (const std::string &str : p.strings) s += " " + QuotedString(str);
    for (uint8_t b : p.bools) s += b ? " true" : " false";
    return s + " ]";
}

const ParsedParameter *Find(const ParsedParameterVector &params, const std::string &name) {
    for (const ParsedParameter &p : params)
        if (p.name == name) return &p;
    return nullptr;
}

}  // namespace

std::string QuotedString(const std::string &text) {
    std::string s = "\"";
    for (char c : text) {
        switch (c) {
        case '"': s += "\\\""; break;
        case '\\': s += "\\\\"; break;
        case '\n': s += "\\n"; break;
        case '\t': s += "\\t"; break;
        case '\r': s += "\\r"; break;
        default: s += c;
        }
    }
    return s + "\"";
}

void FormattingTarget::Line(const std::string &words, const ParsedParameterVector &params) {
    out << std::string(size_t(4 * indent), ' ') << words;
    for (const ParsedParameter &p : params) out << "\n" << std::string(size_t(4 * indent + 4), ' ') << Parameter(p);
    out << "\n";
}

std::optional<std::string> FormattingTarget::WritePLY(const ParsedParameterVector &params, const FileLoc &loc) {
    const ParsedParameter *P = Find(params, "P"), *indices = Find(params, "indices");
    const ParsedParameter *N = Find(params, "N"), *uv = Find(params, "uv");
    if (!P || Find(params, "faceIndices") || Find(params, "S")) return std::nullopt;
    const size_t nVertices = P->numbers.size() / 3;
    std::vector<double> triangles = indices ? indices->numbers : std::vector<double>{0, 1, 2};
    if ((N && N->numbers.size() != 3 * nVertices) || (uv && uv->numbers.size() != 2 * nVertices))
        return std::nullopt;  // the loader reports the mismatch at its line
    std::string name = fmt::format("mesh_{:05d}.ply", ++meshes);
    std::string path = (std::filesystem::path(*plyFolder) / name).string();
    WriteFileAtomically(path, [&](const std::string &tmp) {
        std::ofstream ply(tmp, std::ios::binary);
        ply << "ply\nformat binary_little_endian 1.0\nelement vertex " << nVertices
            << "\nproperty float x\nproperty float y\nproperty float z\n";
        if (N) ply << "property float nx\nproperty float ny\nproperty float nz\n";
        if (uv) ply << "property float u\nproperty float v\n";
        ply << "element face " << triangles.size() / 3 << "\nproperty list uchar int vertex_indices\nend_header\n";
        auto put = [&](auto value) { ply.write(reinterpret_cast<const char *>(&value), sizeof(value)); };
        for (size_t i = 0; i < nVertices; ++i) {
            for (int c = 0; c < 3; ++c) put(float(P->numbers[3 * i + c]));
            if (N)
                for (int c = 0; c < 3; ++c) put(float(N->numbers[3 * i + c]));
            if (uv)
                for (int c = 0; c < 2; ++c) put(float(uv->numbers[2 * i + c]));
        }
        for (size_t t = 0; t + 2 < triangles.size(); t += 3) {
            put(uint8_t(3));
            for (int c = 0; c < 3; ++c) put(int32_t(triangles[t + c]));
        }
        if (!ply) throw ParseError(loc, "--toply: cannot write " + path);
    });
    return name;
}

void FormattingTarget::Entity(const char *directive, std::string name, ParsedParameterVector &params,
                              const FileLoc &loc, UpgradeRule rule) {
    if (upgrade) rule(name, params, loc);
    Line(std::string(directive) + " " + QuotedString(name), params);
}

void FormattingTarget::Shape(const std::string &type, ParsedParameterVector params, FileLoc loc) {
    std::string name = type;
    if (upgrade) UpgradeShape(name, params, loc);
    if (name == "trianglemesh" && plyFolder)
        if (std::optional<std::string> ply = WritePLY(params, loc)) {
            ParsedParameterVector rest;
            for (ParsedParameter &p : params)
                if (p.name != "P" && p.name != "N" && p.name != "uv" && p.name != "indices")
                    rest.push_back(std::move(p));
            ParsedParameter filename;
            filename.type = "string";
            filename.name = "filename";
            filename.strings = {*ply};
            rest.insert(rest.begin(), filename);
            Line("Shape \"plymesh\"", rest);
            return;
        }
    Line("Shape " + QuotedString(name), params);
}

void FormattingTarget::Option(const std::string &name, const std::string &value, FileLoc) {
    bool bare = value == "true" || value == "false" || IsNumberText(value);
    Line("Option " + QuotedString(name) + " " + (bare ? value : QuotedString(value)));
}

void FormattingTarget::Scale(Float sx, Float sy, Float sz, FileLoc) { Line("Scale " + Numbers({sx, sy, sz})); }
void FormattingTarget::Identity(FileLoc) { Line("Identity"); }
void FormattingTarget::Translate(Float dx, Float dy, Float dz, FileLoc) {
    Line("Translate " + Numbers({dx, dy, dz}));
}
void FormattingTarget::Rotate(Float angle, Float ax, Float ay, Float az, FileLoc) {
    Line("Rotate " + Numbers({angle, ax, ay, az}));
}
void FormattingTarget::LookAt(Float ex, Float ey, Float ez, Float lx, Float ly, Float lz, Float ux,
                              Float uy, Float uz, FileLoc) {
    Line("LookAt " + Numbers({ex, ey, ez}) + "\n" + std::string(size_t(4 * indent + 7), ' ') +
         Numbers({lx, ly, lz}) + "\n" + std::string(size_t(4 * indent + 7), ' ') + Numbers({ux, uy, uz}));
}
void FormattingTarget::ConcatTransform(Float m[16], FileLoc) { Line("ConcatTransform " + Matrix(m)); }
void FormattingTarget::Transform(Float m[16], FileLoc) { Line("Transform " + Matrix(m)); }
void FormattingTarget::CoordinateSystem(const std::string &name, FileLoc) {
    Line("CoordinateSystem " + QuotedString(name));
}
void FormattingTarget::CoordSysTransform(const std::string &name, FileLoc) {
    Line("CoordSysTransform " + QuotedString(name));
}
void FormattingTarget::ActiveTransformAll(FileLoc) { Line("ActiveTransform All"); }
void FormattingTarget::ActiveTransformEndTime(FileLoc) { Line("ActiveTransform EndTime"); }
void FormattingTarget::ActiveTransformStartTime(FileLoc) { Line("ActiveTransform StartTime"); }
void FormattingTarget::TransformTimes(Float start, Float end, FileLoc) {
    Line("TransformTimes " + Numbers({start, end}));
}
void FormattingTarget::ColorSpace(const std::string &name, FileLoc) { Line("ColorSpace " + QuotedString(name)); }
void FormattingTarget::PixelFilter(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("PixelFilter", name, params, loc, UpgradePixelFilter);
}
void FormattingTarget::Film(const std::string &type, ParsedParameterVector params, FileLoc loc) {
    Entity("Film", type, params, loc, UpgradeFilm);
}
void FormattingTarget::Sampler(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("Sampler", name, params, loc, UpgradeSampler);
}
void FormattingTarget::Accelerator(const std::string &name, ParsedParameterVector params, FileLoc) {
    Line("Accelerator " + QuotedString(name), params);
}
void FormattingTarget::Integrator(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("Integrator", name, params, loc, UpgradeIntegrator);
}
void FormattingTarget::Camera(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("Camera", name, params, loc, UpgradeCamera);
}
void FormattingTarget::MakeNamedMedium(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    if (upgrade) UpgradeMedium(params, loc);
    Line("MakeNamedMedium " + QuotedString(name), params);
}
void FormattingTarget::MediumInterface(const std::string &inside, const std::string &outside, FileLoc) {
    Line("MediumInterface " + QuotedString(inside) + " " + QuotedString(outside));
}
void FormattingTarget::WorldBegin(FileLoc) {
    out << "\n";
    Line("WorldBegin");
}
void FormattingTarget::AttributeBegin(FileLoc) {
    Line("AttributeBegin");
    ++indent;
}
void FormattingTarget::AttributeEnd(FileLoc) {
    indent = std::max(0, indent - 1);
    Line("AttributeEnd");
}
void FormattingTarget::Attribute(const std::string &target, ParsedParameterVector params, FileLoc) {
    Line("Attribute " + QuotedString(target), params);
}
void FormattingTarget::Texture(const std::string &name, const std::string &type, const std::string &texname,
                               ParsedParameterVector params, FileLoc loc) {
    std::string upgraded = type;
    if (upgrade) UpgradeTexture(upgraded, texname, params, loc);
    Line("Texture " + QuotedString(name) + " " + QuotedString(upgraded) + " " + QuotedString(texname), params);
}
void FormattingTarget::Material(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("Material", name, params, loc, UpgradeMaterial);
}
void FormattingTarget::MakeNamedMaterial(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    if (upgrade) {
        auto type = std::find_if(params.begin(), params.end(), [](const ParsedParameter &p) { return p.name == "type"; });
        std::string upgraded = type != params.end() && type->strings.size() == 1 ? type->strings[0] : "";
        UpgradeMaterial(upgraded, params, loc);  // may add and remove parameters: type is stale
        for (ParsedParameter &p : params)
            if (p.name == "type") p.strings = {upgraded};
    }
    Line("MakeNamedMaterial " + QuotedString(name), params);
}
void FormattingTarget::NamedMaterial(const std::string &name, FileLoc) {
    Line("NamedMaterial " + QuotedString(name));
}
void FormattingTarget::LightSource(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("LightSource", name, params, loc, UpgradeLight);
}
void FormattingTarget::AreaLightSource(const std::string &name, ParsedParameterVector params, FileLoc loc) {
    Entity("AreaLightSource", name, params, loc, UpgradeAreaLight);
}
void FormattingTarget::ReverseOrientation(FileLoc) { Line("ReverseOrientation"); }
void FormattingTarget::ObjectBegin(const std::string &name, FileLoc) {
    Line("ObjectBegin " + QuotedString(name));
    ++indent;
}
void FormattingTarget::ObjectEnd(FileLoc) {
    indent = std::max(0, indent - 1);
    Line("ObjectEnd");
}
void FormattingTarget::ObjectInstance(const std::string &name, FileLoc) {
    Line("ObjectInstance " + QuotedString(name));
}
void FormattingTarget::EndOfFiles() { out.flush(); }

}  // namespace pbrt
