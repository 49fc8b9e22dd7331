// The pbrt-v4 scene file parser (pbrt-v4's parser.h, reduced): text -> tokens -> directives,
// each directive delivered with its FileLoc to a ParserTarget (host only).
//
// The parser checks syntax and the shape of parameter values (a "float" gets numbers, a
// "point3" a multiple of three of them, no NaN or Inf); what a directive means is the target's
// business. Every problem is a ParseError "file:line:col: error: ...".
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/error.h"

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pbrt {

// One "type name" [ values ] of a directive's parameter list. The parser canonicalizes the
// type's aliases (point -> point3, vector -> vector3, normal3 -> normal, color -> rgb) and
// stores the values in the member that suits the type: numbers (integer and all numeric
// types, and a spectrum's (lambda, value) pairs), strings (string, texture, a named or file
// spectrum), bools.
struct ParsedParameter {
    std::string type, name;
    FileLoc loc;
    std::vector<double> numbers;
    std::vector<std::string> strings;
    std::vector<uint8_t> bools;
    // Set by ParameterDictionary lookups, so that ReportUnused() can name what nobody read.
    mutable bool lookedUp = false;

    std::string ToString() const;
};

using ParsedParameterVector = std::vector<ParsedParameter>;

// The receiver of parsed directives (pbrt-v4's ParserTarget). Transform arrays are in
// pbrt-v4's file order (the 16 numbers as written).
class ParserTarget {
  public:
    virtual ~ParserTarget() = default;

    virtual void Scale(Float sx, Float sy, Float sz, FileLoc loc) = 0;
    virtual void Shape(const std::string &name, ParsedParameterVector params, FileLoc loc) = 0;
    virtual void Option(const std::string &name, const std::string &value, FileLoc loc) = 0;
    virtual void Identity(FileLoc loc) = 0;
    virtual void Translate(Float dx, Float dy, Float dz, FileLoc loc) = 0;
    virtual void Rotate(Float angle, Float ax, Float ay, Float az, FileLoc loc) = 0;
    virtual void LookAt(Float ex, Float ey, Float ez, Float lx, Float ly, Float lz, Float ux,
                        Float uy, Float uz, FileLoc loc) = 0;
    virtual void ConcatTransform(Float transform[16], FileLoc loc) = 0;
    virtual void Transform(Float transform[16], FileLoc loc) = 0;
    virtual void CoordinateSystem(const std::string &name, FileLoc loc) = 0;
    virtual void CoordSysTransform(const std::string &name, FileLoc loc) = 0;
    virtual void ActiveTransformAll(FileLoc loc) = 0;
    virtual void ActiveTransformEndTime(FileLoc loc) = 0;
    virtual void ActiveTransformStartTime(FileLoc loc) = 0;
    virtual void TransformTimes(Float start, Float end, FileLoc loc) = 0;
    virtual void ColorSpace(const std::string &name, FileLoc loc) = 0;
    virtual void PixelFilter(const std::string &name, ParsedParameterVector params,
                             FileLoc loc) = 0;
    virtual void Film(const std::string &type, ParsedParameterVector params, FileLoc loc) = 0;
    virtual void Sampler(const std::string &name, ParsedParameterVector params,
                         FileLoc loc) = 0;
    virtual void Accelerator(const std::string &name, ParsedParameterVector params,
                             FileLoc loc) = 0;
    virtual void Integrator(const std::string &name, ParsedParameterVector params,
                            FileLoc loc) = 0;
    virtual void Camera(const std::string &name, ParsedParameterVector params,
                        FileLoc loc) = 0;
    virtual void MakeNamedMedium(const std::string &name, ParsedParameterVector params,
                                 FileLoc loc) = 0;
    virtual void MediumInterface(const std::string &insideName, const std::string &outsideName,
                                 FileLoc loc) = 0;
    virtual void WorldBegin(FileLoc loc) = 0;
    virtual void AttributeBegin(FileLoc loc) = 0;
    virtual void AttributeEnd(FileLoc loc) = 0;
    virtual void Attribute(const std::string &target, ParsedParameterVector params,
                           FileLoc loc) = 0;
    virtual void Texture(const std::string &name, const std::string &type,
                         const std::string &texname, ParsedParameterVector params,
                         FileLoc loc) = 0;
    virtual void Material(const std::string &name, ParsedParameterVector params,
                          FileLoc loc) = 0;
    virtual void MakeNamedMaterial(const std::string &name, ParsedParameterVector params,
                                   FileLoc loc) = 0;
    virtual void NamedMaterial(const std::string &name, FileLoc loc) = 0;
    virtual void LightSource(const std::string &name, ParsedParameterVector params,
                             FileLoc loc) = 0;
    virtual void AreaLightSource(const std::string &name, ParsedParameterVector params,
                                 FileLoc loc) = 0;
    virtual void ReverseOrientation(FileLoc loc) = 0;
    virtual void ObjectBegin(const std::string &name, FileLoc loc) = 0;
    virtual void ObjectEnd(FileLoc loc) = 0;
    virtual void ObjectInstance(const std::string &name, FileLoc loc) = 0;
    virtual void EndOfFiles() = 0;
};

// Parses a scene file and everything it Includes/Imports, then calls target->EndOfFiles().
void ParseFile(ParserTarget *target, const std::string &filename);
// A scene file to parse: read from its name, or its text already read (standard input).
struct SceneFile {
    std::string filename;
    std::optional<std::string> text;
};
// Several files in order, as one scene (pbrt-v4's ParseFiles); then target->EndOfFiles().
void ParseFiles(ParserTarget *target, const std::vector<SceneFile> &files);
// The same for scene text held in memory; relative Include paths resolve against the
// current directory, and locations name the text `name`.
void ParseString(ParserTarget *target, std::string text, std::string name = "<string>");

// A token: a bare word or number, a quoted string (text keeps its quotes and escapes), or
// "[" / "]". text points into the Tokenizer's buffer. The location is kept as two ints, not a
// FileLoc, because large meshes are millions of tokens and only a few ever need a FileLoc.
struct Token {
    std::string_view text;
    int line = 1, column = 1;

    bool IsQuoted() const { return !text.empty() && text.front() == '"'; }
};

// Splits pbrt-v4 scene text into tokens: whitespace separates, "#" comments run to the end of
// the line, strings are double-quoted on one line with the escapes \b \f \n \r \t \\ \' \".
class Tokenizer {
  public:
    Tokenizer(std::string contents, std::string filename);
    // Reads the whole file in one go; a missing or unreadable file is a ParseError at
    // `includedAt` (the Include directive), or at the file itself when null.
    static Tokenizer FromFile(const std::string &filename, const FileLoc *includedAt);

    // The next token, or nullopt at the end of the text.
    std::optional<Token> Next();

    FileLoc Loc(const Token &token) const { return {filename, token.line, token.column}; }
    // Where the text ends, for "premature end of file" errors.
    FileLoc EndLoc() const { return {filename, line, column}; }
    const std::string &Filename() const { return filename; }
    size_t Size() const { return contents.size(); }

    // The value of a quoted-string token, quotes removed and escapes decoded.
    static std::string Dequote(const Token &token);

  private:
    Token ScanString(Token token);
    Token ScanWord(Token token);
    void Advance();
    [[noreturn]] void ErrorHere(int line, int column, const std::string &message) const;

    std::string contents, filename;
    size_t pos = 0;
    int line = 1, column = 1;
};

}  // namespace pbrt
