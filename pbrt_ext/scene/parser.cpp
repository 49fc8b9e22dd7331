#include "pbrt_ext/scene/parser.h"

#include "pbrt_ext/scene/paramdict.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <array>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <utility>

namespace pbrt {

namespace {

constexpr int kMaxIncludeDepth = 64;
// Long tokens (a misplaced string of a whole file, say) are cut short in messages.
constexpr size_t kMaxTokenShown = 40;

bool IsSpace(char c) {
    return c == ' ' || c == '\n' || c == '\t' || c == '\r' || c == '\v' || c == '\f';
}

bool IsDelimiter(char c) { return IsSpace(c) || c == '"' || c == '[' || c == ']' || c == '#'; }

// Directives and numbers are made of these; anything else outside strings and comments is
// a mistake worth pointing at rather than a token that fails later with a vaguer message.
bool IsWordChar(char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
           c == '+' || c == '-' || c == '.' || c == '_';
}

std::string ShowChar(char c) {
    if (c >= 0x20 && c < 0x7f)
        return std::string("'") + c + "'";
    static constexpr char kHex[] = "0123456789abcdef";
    auto u = static_cast<unsigned char>(c);
    return std::string("byte 0x") + kHex[u >> 4] + kHex[u & 15];
}

std::string Show(const Token &token) {
    if (token.text.size() <= kMaxTokenShown)
        return std::string(token.text);
    return std::string(token.text.substr(0, kMaxTokenShown)) + "...";
}

char DecodeEscape(char c) {
    switch (c) {
    case 'b': return '\b';
    case 'f': return '\f';
    case 'n': return '\n';
    case 'r': return '\r';
    case 't': return '\t';
    case '\\': return '\\';
    case '\'': return '\'';
    case '"': return '"';
    default: return 0;
    }
}

std::string FormatNumber(double v) {
    char buf[32];
    auto result = std::to_chars(buf, buf + sizeof(buf), v);
    return std::string(buf, result.ptr);
}

// The value of a number token; nullopt when the token is not entirely a number. Infinities
// and NaNs parse here and are rejected by the caller, which can name the parameter.
std::optional<double> ParseNumber(std::string_view s) {
    if (s.size() > 1 && s[0] == '+' && s[1] != '-')
        s.remove_prefix(1);
    double v = 0;
    auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
    if (end != s.data() + s.size() || s.empty())
        return {};
    if (ec == std::errc::result_out_of_range)
        return std::numeric_limits<double>::infinity();
    return v;
}

// Values are used as Float, so 1e39 is as unusable as an Inf.
bool IsFiniteFloat(double v) {
    return std::isfinite(v) && std::abs(v) <= std::numeric_limits<Float>::max();
}

}  // namespace

///////////////////////////////////////////////////////////////////////////
// ParsedParameter

std::string ParsedParameter::ToString() const {
    std::string s = "\"" + type + " " + name + "\" [";
    for (double v : numbers)
        s += " " + FormatNumber(v);
    for (const std::string &str : strings)
        s += " \"" + str + "\"";
    for (uint8_t b : bools)
        s += b ? " true" : " false";
    return s + " ]";
}

///////////////////////////////////////////////////////////////////////////
// Tokenizer

Tokenizer::Tokenizer(std::string text, std::string name)
    : contents(std::move(text)), filename(std::move(name)) {
    auto byte = [&](size_t i) { return static_cast<unsigned char>(contents[i]); };
    if (contents.size() >= 2 &&
        ((byte(0) == 0xfe && byte(1) == 0xff) || (byte(0) == 0xff && byte(1) == 0xfe)))
        ErrorHere(1, 1, "the file is encoded as UTF-16: expected UTF-8 or ASCII text");
    // A UTF-8 byte order mark is legal UTF-8 that some editors write; it is not a token.
    if (contents.size() >= 3 && byte(0) == 0xef && byte(1) == 0xbb && byte(2) == 0xbf)
        pos = 3;
}

Tokenizer Tokenizer::FromFile(const std::string &filename, const FileLoc *includedAt) {
    auto fail = [&](const std::string &why) {
        if (includedAt)
            throw ParseError(*includedAt, "cannot open included file \"" + filename + "\": " + why);
        throw ParseError(FileLoc{filename, 0, 0}, "cannot open file: " + why);
    };
    std::string why;
    std::optional<uint64_t> size = RegularFileSize(filename, &why);
    if (!size)
        fail(why);
    CheckMemory(includedAt ? *includedAt : FileLoc{filename, 0, 0},
                fmt::format("parsing the {}-byte file \"{}\"", *size, filename),
                SaturatingProduct({*size, kParsedTextBytesPerByte}));
    std::ifstream in(filename, std::ios::binary);
    std::string text(*size, '\0');
    if (!in.read(text.data(), std::streamsize(*size)))
        fail("read error");
    return Tokenizer(std::move(text), filename);
}

void Tokenizer::Advance() {
    if (contents[pos++] == '\n') {
        ++line;
        column = 1;
    } else
        ++column;
}

void Tokenizer::ErrorHere(int errLine, int errColumn, const std::string &message) const {
    throw ParseError(FileLoc{filename, errLine, errColumn}, message);
}

std::optional<Token> Tokenizer::Next() {
    while (pos < contents.size()) {
        char c = contents[pos];
        Token token{std::string_view(contents).substr(pos, 1), line, column};
        if (IsSpace(c))
            Advance();
        else if (c == '#')
            while (pos < contents.size() && contents[pos] != '\n')
                Advance();
        else if (c == '"')
            return ScanString(token);
        else if (c == '[' || c == ']') {
            Advance();
            return token;
        } else
            return ScanWord(token);
    }
    return {};
}

Token Tokenizer::ScanString(Token token) {
    size_t start = pos;
    Advance();
    while (true) {
        if (pos == contents.size())
            ErrorHere(token.line, token.column,
                      "unterminated string: expected a closing '\"' before the end of the file");
        char c = contents[pos];
        if (c == '\n')
            ErrorHere(token.line, token.column,
                      "unterminated string: expected a closing '\"' before the end of the line");
        if (c == '"')
            break;
        if (c == '\\' && pos + 1 < contents.size() && contents[pos + 1] != '\n') {
            if (!DecodeEscape(contents[pos + 1]))
                ErrorHere(line, column,
                          std::string("unknown escape sequence \"\\") + contents[pos + 1] +
                              "\": expected one of \\b \\f \\n \\r \\t \\\\ \\' \\\"");
            Advance();
        }
        Advance();
    }
    Advance();
    token.text = std::string_view(contents).substr(start, pos - start);
    return token;
}

Token Tokenizer::ScanWord(Token token) {
    size_t start = pos;
    while (pos < contents.size() && !IsDelimiter(contents[pos])) {
        if (!IsWordChar(contents[pos]))
            ErrorHere(line, column,
                      "unexpected character " + ShowChar(contents[pos]) +
                          ": expected a directive, a number, a quoted string, \"[\" or \"]\"");
        Advance();
    }
    token.text = std::string_view(contents).substr(start, pos - start);
    return token;
}

std::string Tokenizer::Dequote(const Token &token) {
    std::string_view body = token.text.substr(1, token.text.size() - 2);
    std::string s;
    s.reserve(body.size());
    for (size_t i = 0; i < body.size(); ++i)
        s.push_back(body[i] == '\\' ? DecodeEscape(body[++i]) : body[i]);
    return s;
}

///////////////////////////////////////////////////////////////////////////
// Parser

namespace {

using NoArgDirective = void (ParserTarget::*)(FileLoc);
using NameDirective = void (ParserTarget::*)(const std::string &, FileLoc);
using ParamDirective = void (ParserTarget::*)(const std::string &, ParsedParameterVector,
                                              FileLoc);

template <typename F, size_t N>
F FindDirective(const std::array<std::pair<std::string_view, F>, N> &table,
                std::string_view name) {
    for (const auto &[directive, f] : table)
        if (directive == name)
            return f;
    return nullptr;
}

constexpr std::array<std::pair<std::string_view, NoArgDirective>, 6> kNoArgDirectives = {{
    {"AttributeBegin", &ParserTarget::AttributeBegin},
    {"AttributeEnd", &ParserTarget::AttributeEnd},
    {"Identity", &ParserTarget::Identity},
    {"ObjectEnd", &ParserTarget::ObjectEnd},
    {"ReverseOrientation", &ParserTarget::ReverseOrientation},
    {"WorldBegin", &ParserTarget::WorldBegin},
}};

constexpr std::array<std::pair<std::string_view, NameDirective>, 6> kNameDirectives = {{
    {"ColorSpace", &ParserTarget::ColorSpace},
    {"CoordinateSystem", &ParserTarget::CoordinateSystem},
    {"CoordSysTransform", &ParserTarget::CoordSysTransform},
    {"NamedMaterial", &ParserTarget::NamedMaterial},
    {"ObjectBegin", &ParserTarget::ObjectBegin},
    {"ObjectInstance", &ParserTarget::ObjectInstance},
}};

constexpr std::array<std::pair<std::string_view, ParamDirective>, 13> kParamDirectives = {{
    {"Accelerator", &ParserTarget::Accelerator},
    {"AreaLightSource", &ParserTarget::AreaLightSource},
    {"Attribute", &ParserTarget::Attribute},
    {"Camera", &ParserTarget::Camera},
    {"Film", &ParserTarget::Film},
    {"Integrator", &ParserTarget::Integrator},
    {"LightSource", &ParserTarget::LightSource},
    {"MakeNamedMaterial", &ParserTarget::MakeNamedMaterial},
    {"MakeNamedMedium", &ParserTarget::MakeNamedMedium},
    {"Material", &ParserTarget::Material},
    {"PixelFilter", &ParserTarget::PixelFilter},
    {"Sampler", &ParserTarget::Sampler},
    {"Shape", &ParserTarget::Shape},
}};

std::string KnownParameterTypes() {
    static constexpr std::string_view kNames[] = {
        "integer", "float", "point2", "vector2", "point3", "vector3", "normal",
        "rgb", "blackbody", "spectrum", "bool", "string", "texture"};
    std::string s;
    for (std::string_view n : kNames)
        s += std::string(s.empty() ? "" : ", ") + std::string(n);
    return s;
}

class Parser {
  public:
    explicit Parser(ParserTarget *target) : target(target) {}

    void Run(Tokenizer file);

  private:
    FileLoc Loc(const Token &t) const { return files.back()->Loc(t); }
    [[noreturn]] void Unexpected(const Token &t, const std::string &expected) const {
        throw ParseError(Loc(t), "unexpected " + Show(t) + ": expected " + expected);
    }

    // Tokens come from the innermost file only: a directive and its arguments never span
    // an Include boundary.
    std::optional<Token> NextOptional();
    Token NextRequired(const std::string &expected);

    void Directive(const Token &t);
    bool SpecialDirective(std::string_view d, const FileLoc &loc);
    std::string ReadString(std::string_view directive);
    Float ReadNumber(std::string_view directive);
    template <int N>
    std::array<Float, N> ReadNumbers(std::string_view directive);
    void ReadMatrix(std::string_view directive, Float m[16]);
    ParsedParameterVector ReadParameters();
    ParsedParameter ReadDeclaration(const Token &t);
    void AddValue(ParsedParameter &p, const ParameterTypeInfo &info, const Token &t);
    void Include(std::string_view directive, const FileLoc &loc);

    ParserTarget *target;
    // unique_ptr: tokens view the Tokenizer's buffer, which must not move as the stack grows.
    std::vector<std::unique_ptr<Tokenizer>> files;
    std::optional<Token> pending;
    bool warnedTransformBlock = false, warnedWorldEnd = false;
    // Every file parsed so far, the main one included.
    int filesRead = 0;
    uint64_t bytesRead = 0;
};

void Parser::Run(Tokenizer file) {
    filesRead = 1;
    bytesRead = file.Size();
    files.push_back(std::make_unique<Tokenizer>(std::move(file)));
    while (!files.empty()) {
        if (std::optional<Token> t = NextOptional())
            Directive(*t);
        else
            files.pop_back();
    }
}

std::optional<Token> Parser::NextOptional() {
    if (pending)
        return std::exchange(pending, std::nullopt);
    return files.back()->Next();
}

Token Parser::NextRequired(const std::string &expected) {
    std::optional<Token> t = NextOptional();
    if (!t)
        throw ParseError(files.back()->EndLoc(), "premature end of file: expected " + expected);
    return *t;
}

void Parser::Directive(const Token &t) {
    std::string_view d = t.text;
    FileLoc loc = Loc(t);
    if (NoArgDirective noArg = FindDirective(kNoArgDirectives, d))
        (target->*noArg)(loc);
    else if (NameDirective named = FindDirective(kNameDirectives, d))
        (target->*named)(ReadString(d), loc);
    else if (ParamDirective withParams = FindDirective(kParamDirectives, d)) {
        std::string name = ReadString(d);
        (target->*withParams)(name, ReadParameters(), loc);
    } else if (!SpecialDirective(d, loc)) {
        if (t.IsQuoted() || d == "[" || d == "]" || ParseNumber(d))
            Unexpected(t, "a directive");
        throw ParseError(loc, "unknown directive \"" + std::string(d) + "\"");
    }
}

// The directives whose arguments are not a name and a parameter list.
bool Parser::SpecialDirective(std::string_view d, const FileLoc &loc) {
    if (d == "Translate" || d == "Scale") {
        auto v = ReadNumbers<3>(d);
        (target->*(d == "Scale" ? &ParserTarget::Scale : &ParserTarget::Translate))(v[0], v[1],
                                                                                   v[2], loc);
    } else if (d == "Rotate") {
        auto v = ReadNumbers<4>(d);
        target->Rotate(v[0], v[1], v[2], v[3], loc);
    } else if (d == "LookAt") {
        auto v = ReadNumbers<9>(d);
        target->LookAt(v[0], v[1], v[2], v[3], v[4], v[5], v[6], v[7], v[8], loc);
    } else if (d == "Transform" || d == "ConcatTransform") {
        Float m[16];
        ReadMatrix(d, m);
        if (d == "Transform")
            target->Transform(m, loc);
        else
            target->ConcatTransform(m, loc);
    } else if (d == "TransformTimes") {
        auto v = ReadNumbers<2>(d);
        target->TransformTimes(v[0], v[1], loc);
    } else if (d == "ActiveTransform") {
        Token a = NextRequired("All, StartTime or EndTime for ActiveTransform");
        if (a.text == "All")
            target->ActiveTransformAll(loc);
        else if (a.text == "StartTime")
            target->ActiveTransformStartTime(loc);
        else if (a.text == "EndTime")
            target->ActiveTransformEndTime(loc);
        else
            Unexpected(a, "All, StartTime or EndTime for ActiveTransform");
    } else if (d == "Texture") {
        std::string name = ReadString(d);
        std::string type = ReadString(d);
        std::string texName = ReadString(d);
        target->Texture(name, type, texName, ReadParameters(), loc);
    } else if (d == "Option") {
        std::string name = ReadString(d);
        Token v = NextRequired("a value for Option");
        target->Option(name, v.IsQuoted() ? Tokenizer::Dequote(v) : std::string(v.text), loc);
    } else if (d == "MediumInterface") {
        std::string inside = ReadString(d);
        std::string outside = inside;
        std::optional<Token> t = NextOptional();
        if (t && t->IsQuoted())
            outside = Tokenizer::Dequote(*t);
        else
            pending = t;
        target->MediumInterface(inside, outside, loc);
    } else if (d == "Include" || d == "Import") {
        // Import is pbrt-v4's Include that may be parsed in parallel; here it is an Include.
        Include(d, loc);
    } else if (d == "TransformBegin" || d == "TransformEnd") {
        if (!std::exchange(warnedTransformBlock, true))
            WarningAt(loc, "TransformBegin/TransformEnd are pbrt-v3 directives: treated as "
                           "AttributeBegin/AttributeEnd");
        if (d == "TransformBegin")
            target->AttributeBegin(loc);
        else
            target->AttributeEnd(loc);
    } else if (d == "WorldEnd") {
        if (!std::exchange(warnedWorldEnd, true))
            WarningAt(loc, "WorldEnd is a pbrt-v3 directive: ignored");
    } else
        return false;
    return true;
}

std::string Parser::ReadString(std::string_view directive) {
    std::string expected = "a quoted string for " + std::string(directive);
    Token t = NextRequired(expected);
    if (!t.IsQuoted())
        Unexpected(t, expected);
    return Tokenizer::Dequote(t);
}

Float Parser::ReadNumber(std::string_view directive) {
    std::string expected = "a number for " + std::string(directive);
    Token t = NextRequired(expected);
    std::optional<double> v = ParseNumber(t.text);
    if (!v)
        Unexpected(t, expected);
    if (!IsFiniteFloat(*v))
        throw ParseError(Loc(t), "non-finite value " + Show(t) + " for " +
                                     std::string(directive) + ": expected a finite number");
    return Float(*v);
}

template <int N>
std::array<Float, N> Parser::ReadNumbers(std::string_view directive) {
    std::array<Float, N> v;
    for (Float &x : v)
        x = ReadNumber(directive);
    return v;
}

void Parser::ReadMatrix(std::string_view directive, Float m[16]) {
    std::string name(directive);
    Token open = NextRequired("\"[\" for " + name);
    if (open.text != "[")
        Unexpected(open, "\"[\" for " + name);
    for (int i = 0; i < 16; ++i)
        m[i] = ReadNumber(directive);
    Token close = NextRequired("\"]\" after the 16 numbers of " + name);
    if (close.text != "]")
        Unexpected(close, "\"]\" after the 16 numbers of " + name);
}

ParsedParameterVector Parser::ReadParameters() {
    ParsedParameterVector params;
    while (std::optional<Token> t = NextOptional()) {
        if (!t->IsQuoted()) {
            pending = t;
            break;
        }
        ParsedParameter p = ReadDeclaration(*t);
        const ParameterTypeInfo &info = *LookupParameterType(p.type);
        std::string decl = "\"" + p.type + " " + p.name + "\"";
        Token v = NextRequired("a value or \"[\" for " + decl);
        if (v.text == "[") {
            while ((v = NextRequired("\"]\" closing the values of " + decl)).text != "]")
                AddValue(p, info, v);
        } else
            AddValue(p, info, v);
        CheckValueCount(p);
        params.push_back(std::move(p));
    }
    return params;
}

ParsedParameter Parser::ReadDeclaration(const Token &t) {
    std::string decl = Tokenizer::Dequote(t);
    ParsedParameter p;
    p.loc = Loc(t);
    size_t typeBegin = decl.find_first_not_of(" \t");
    size_t typeEnd = decl.find_first_of(" \t", typeBegin);
    size_t nameBegin = decl.find_first_not_of(" \t", typeEnd);
    size_t nameEnd = decl.find_first_of(" \t", nameBegin);
    bool trailing = decl.find_first_not_of(" \t", nameEnd) != std::string::npos;
    if (nameBegin == std::string::npos || trailing)
        throw ParseError(p.loc, "bad parameter declaration \"" + decl +
                                    "\": expected \"type name\", such as \"float fov\"");
    std::string_view type = CanonicalParameterType(
        std::string_view(decl).substr(typeBegin, typeEnd - typeBegin));
    if (!LookupParameterType(type))
        throw ParseError(p.loc, "unknown parameter type \"" + std::string(type) + "\" in \"" +
                                    decl + "\": expected one of " + KnownParameterTypes());
    p.type = type;
    p.name = decl.substr(nameBegin, nameEnd - nameBegin);
    return p;
}

void Parser::AddValue(ParsedParameter &p, const ParameterTypeInfo &info, const Token &t) {
    std::string decl = "\"" + p.type + " " + p.name + "\"";
    bool isBool = t.text == "true" || t.text == "false" || t.text == "\"true\"" ||
                  t.text == "\"false\"";
    switch (info.kind) {
    case ParameterValueKind::Bool:
        if (!isBool)
            Unexpected(t, "bool values (true or false) for " + decl);
        p.bools.push_back(t.text.find("true") != std::string_view::npos);
        return;
    case ParameterValueKind::String:
        if (!t.IsQuoted())
            Unexpected(t, "string values for " + decl);
        p.strings.push_back(Tokenizer::Dequote(t));
        return;
    case ParameterValueKind::Spectrum:
        // The first value decides: (lambda, value) numbers or one name / file name.
        if (t.IsQuoted() && p.numbers.empty()) {
            p.strings.push_back(Tokenizer::Dequote(t));
            return;
        }
        if (!p.strings.empty())
            Unexpected(t, "string values for " + decl);
        break;
    case ParameterValueKind::Integer: {
        std::string_view s = t.text.substr(!t.text.empty() && t.text[0] == '+' ? 1 : 0);
        long long i = 0;
        auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), i);
        if (s.empty() || end != s.data() + s.size())
            Unexpected(t, "integer values for " + decl);
        if (ec != std::errc() || i < std::numeric_limits<int>::lowest() ||
            i > std::numeric_limits<int>::max())
            throw ParseError(Loc(t), "integer " + Show(t) + " for " + decl +
                                         " is out of range: expected a 32-bit integer");
        p.numbers.push_back(double(i));
        return;
    }
    case ParameterValueKind::Number:
        break;
    }
    std::optional<double> v = ParseNumber(t.text);
    if (!v)
        Unexpected(t, info.kind == ParameterValueKind::Spectrum && p.numbers.empty()
                          ? "float values or a quoted string for " + decl
                          : "float values for " + decl);
    if (!IsFiniteFloat(*v))
        throw ParseError(Loc(t), "non-finite value " + Show(t) + " for " + decl +
                                     ": expected a finite number");
    p.numbers.push_back(*v);
}

void Parser::Include(std::string_view directive, const FileLoc &loc) {
    std::filesystem::path name = ReadString(directive);
    if (files.size() > kMaxIncludeDepth)
        throw ParseError(loc, "Include nesting deeper than " + std::to_string(kMaxIncludeDepth) +
                                  " (recursive Include?)");
    // As pbrt-v4 resolves every file name: against the main file's folder, also inside an
    // included file.
    if (name.is_relative())
        name = std::filesystem::path(files.front()->Filename()).parent_path() / name;
    files.push_back(std::make_unique<Tokenizer>(Tokenizer::FromFile(name.string(), &loc)));
    // Each file fits the budget alone, but the scene keeps what all of them describe, and a few
    // files that include each other twice describe exponentially much.
    ++filesRead;
    bytesRead += files.back()->Size();
    CheckMemory(loc, fmt::format("parsing {} files of {} bytes in all", filesRead, bytesRead),
                SaturatingProduct({bytesRead, kParsedTextBytesPerByte}));
}

}  // namespace

void ParseFile(ParserTarget *target, const std::string &filename) {
    Parser(target).Run(Tokenizer::FromFile(filename, nullptr));
    target->EndOfFiles();
}

void ParseFiles(ParserTarget *target, const std::vector<SceneFile> &files) {
    for (const SceneFile &file : files)
        Parser(target).Run(file.text ? Tokenizer(*file.text, file.filename)
                                     : Tokenizer::FromFile(file.filename, nullptr));
    target->EndOfFiles();
}

void ParseString(ParserTarget *target, std::string text, std::string name) {
    Parser(target).Run(Tokenizer(std::move(text), std::move(name)));
    target->EndOfFiles();
}

}  // namespace pbrt
