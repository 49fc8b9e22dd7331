// The scene-file parser: tokens with their locations, every directive reaching the target with
// its arguments and FileLoc, parameter values checked against their declared type, Include
// resolution, and the exact text of every syntax error (inline and in tests/data/bad/parse_*).
#include "pbrt_ext/scene/parser.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace pbrt {
namespace {

const std::string kBad = std::string(PBRT_EXT_TEST_DATA_DIR) + "/bad/";

// Writes every call as one line, "Directive args... @file:line:col", so that a test states
// the whole expected call sequence as text.
class RecordingTarget : public ParserTarget {
  public:
    std::vector<std::string> calls;

    void Scale(Float x, Float y, Float z, FileLoc loc) override {
        Add("Scale " + Nums({x, y, z}), loc);
    }
    void Shape(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Shape " + n + Params(p), loc);
    }
    void Option(const std::string &n, const std::string &v, FileLoc loc) override {
        Add("Option " + n + " = " + v, loc);
    }
    void Identity(FileLoc loc) override { Add("Identity", loc); }
    void Translate(Float x, Float y, Float z, FileLoc loc) override {
        Add("Translate " + Nums({x, y, z}), loc);
    }
    void Rotate(Float a, Float x, Float y, Float z, FileLoc loc) override {
        Add("Rotate " + Nums({a, x, y, z}), loc);
    }
    void LookAt(Float ex, Float ey, Float ez, Float lx, Float ly, Float lz, Float ux, Float uy,
                Float uz, FileLoc loc) override {
        Add("LookAt " + Nums({ex, ey, ez, lx, ly, lz, ux, uy, uz}), loc);
    }
    void ConcatTransform(Float m[16], FileLoc loc) override {
        Add("ConcatTransform " + Nums({m[0], m[5], m[15]}), loc);
    }
    void Transform(Float m[16], FileLoc loc) override {
        Add("Transform " + Nums({m[0], m[5], m[15]}), loc);
    }
    void CoordinateSystem(const std::string &n, FileLoc loc) override {
        Add("CoordinateSystem " + n, loc);
    }
    void CoordSysTransform(const std::string &n, FileLoc loc) override {
        Add("CoordSysTransform " + n, loc);
    }
    void ActiveTransformAll(FileLoc loc) override { Add("ActiveTransformAll", loc); }
    void ActiveTransformEndTime(FileLoc loc) override { Add("ActiveTransformEndTime", loc); }
    void ActiveTransformStartTime(FileLoc loc) override { Add("ActiveTransformStartTime", loc); }
    void TransformTimes(Float s, Float e, FileLoc loc) override {
        Add("TransformTimes " + Nums({s, e}), loc);
    }
    void ColorSpace(const std::string &n, FileLoc loc) override { Add("ColorSpace " + n, loc); }
    void PixelFilter(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("PixelFilter " + n + Params(p), loc);
    }
    void Film(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Film " + n + Params(p), loc);
    }
    void Sampler(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Sampler " + n + Params(p), loc);
    }
    void Accelerator(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Accelerator " + n + Params(p), loc);
    }
    void Integrator(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Integrator " + n + Params(p), loc);
    }
    void Camera(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Camera " + n + Params(p), loc);
    }
    void MakeNamedMedium(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("MakeNamedMedium " + n + Params(p), loc);
    }
    void MediumInterface(const std::string &in, const std::string &out, FileLoc loc) override {
        Add("MediumInterface " + in + " " + out, loc);
    }
    void WorldBegin(FileLoc loc) override { Add("WorldBegin", loc); }
    void AttributeBegin(FileLoc loc) override { Add("AttributeBegin", loc); }
    void AttributeEnd(FileLoc loc) override { Add("AttributeEnd", loc); }
    void Attribute(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Attribute " + n + Params(p), loc);
    }
    void Texture(const std::string &n, const std::string &type, const std::string &texName,
                 ParsedParameterVector p, FileLoc loc) override {
        Add("Texture " + n + " " + type + " " + texName + Params(p), loc);
    }
    void Material(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("Material " + n + Params(p), loc);
    }
    void MakeNamedMaterial(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("MakeNamedMaterial " + n + Params(p), loc);
    }
    void NamedMaterial(const std::string &n, FileLoc loc) override {
        Add("NamedMaterial " + n, loc);
    }
    void LightSource(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("LightSource " + n + Params(p), loc);
    }
    void AreaLightSource(const std::string &n, ParsedParameterVector p, FileLoc loc) override {
        Add("AreaLightSource " + n + Params(p), loc);
    }
    void ReverseOrientation(FileLoc loc) override { Add("ReverseOrientation", loc); }
    void ObjectBegin(const std::string &n, FileLoc loc) override { Add("ObjectBegin " + n, loc); }
    void ObjectEnd(FileLoc loc) override { Add("ObjectEnd", loc); }
    void ObjectInstance(const std::string &n, FileLoc loc) override {
        Add("ObjectInstance " + n, loc);
    }
    void EndOfFiles() override { calls.push_back("EndOfFiles"); }

    ParsedParameterVector lastParams;

  private:
    void Add(const std::string &call, const FileLoc &loc) {
        calls.push_back(call + " @" + loc.ToString());
    }
    static std::string Nums(std::initializer_list<Float> v) {
        std::string s;
        for (Float x : v)
            s += fmt::format("{}{}", s.empty() ? "" : " ", int(x));
        return s;
    }
    std::string Params(const ParsedParameterVector &p) {
        lastParams = p;
        std::string s;
        for (const ParsedParameter &param : p)
            if (param.numbers.size() <= kMaxRecordedValues)
                s += fmt::format(" {}@{}", param.ToString(), param.loc.ToString());
        return s;
    }
    // Large meshes are checked through lastParams, not their text.
    static constexpr size_t kMaxRecordedValues = 16;
};

std::vector<std::string> Parse(const std::string &text) {
    RecordingTarget target;
    ParseString(&target, text);
    return target.calls;
}

// The message of the ParseError that parsing `text` throws ("" if none).
std::string ErrorOf(const std::string &text) {
    RecordingTarget target;
    try {
        ParseString(&target, text);
    } catch (const ParseError &e) {
        return e.what();
    }
    return "";
}

std::string FileErrorOf(const std::string &filename) {
    RecordingTarget target;
    try {
        ParseFile(&target, filename);
    } catch (const ParseError &e) {
        return e.what();
    }
    return "";
}

// The tokens of `text`; they view the tokenizer's buffer, so the caller keeps it alive.
std::vector<Token> Tokens(Tokenizer &tokenizer, std::vector<std::string> *texts) {
    std::vector<Token> tokens;
    while (std::optional<Token> t = tokenizer.Next()) {
        tokens.push_back(*t);
        texts->push_back(std::string(t->text));
    }
    return tokens;
}

// Tokenizer

TEST(Tokenizer, SplitsWordsStringsBracketsAndSkipsComments) {
    std::vector<std::string> texts;
    Tokenizer tokenizer("Shape \"sphere\"# note\n  [1 -2.5e3]\"a b\"x", "t");
    std::vector<Token> t = Tokens(tokenizer, &texts);
    EXPECT_EQ(texts, (std::vector<std::string>{"Shape", "\"sphere\"", "[", "1", "-2.5e3", "]",
                                               "\"a b\"", "x"}));
    EXPECT_EQ(t[0].line, 1);
    EXPECT_EQ(t[0].column, 1);
    EXPECT_EQ(t[1].column, 7);
    EXPECT_EQ(t[2].line, 2);
    EXPECT_EQ(t[2].column, 3);
    EXPECT_EQ(t[4].column, 6);
    EXPECT_EQ(t[7].column, 18);
}

TEST(Tokenizer, WordsEndAtEveryDelimiter) {
    std::vector<std::string> texts;
    Tokenizer tokenizer("a\"b\"c[d]e#f\n\fg\vx_1 # a comment that ends the file", "t");
    Tokens(tokenizer, &texts);
    EXPECT_EQ(texts, (std::vector<std::string>{"a", "\"b\"", "c", "[", "d", "]", "e", "g", "x_1"}));
}

TEST(Tokenizer, HandlesCrLfAndTabsAndUtf8ByteOrderMark) {
    std::vector<std::string> texts;
    Tokenizer tokenizer("\xef\xbb\xbfWorldBegin\r\n\tShape", "t");
    std::vector<Token> t = Tokens(tokenizer, &texts);
    EXPECT_EQ(texts, (std::vector<std::string>{"WorldBegin", "Shape"}));
    EXPECT_EQ(t[1].line, 2);
    EXPECT_EQ(t[1].column, 2);
}

TEST(Tokenizer, DequoteDecodesEveryEscape) {
    std::vector<std::string> texts;
    Tokenizer tokenizer(R"("a\"b\\c\n\t\'\b\f\r")", "t");
    std::vector<Token> t = Tokens(tokenizer, &texts);
    ASSERT_EQ(t.size(), 1u);
    EXPECT_EQ(Tokenizer::Dequote(t[0]), "a\"b\\c\n\t'\b\f\r");
}

TEST(Tokenizer, ReportsUnterminatedStringsAtTheirStart) {
    EXPECT_EQ(ErrorOf("Shape \"sphere\nWorldBegin"),
              "<string>:1:7: error: unterminated string: expected a closing '\"' before the end "
              "of the line");
    EXPECT_EQ(ErrorOf("Shape\n  \"sph"),
              "<string>:2:3: error: unterminated string: expected a closing '\"' before the end "
              "of the file");
    EXPECT_EQ(ErrorOf("Shape \"sph\\"),
              "<string>:1:7: error: unterminated string: expected a closing '\"' before the end "
              "of the file");
    // A backslash does not continue a string onto the next line.
    EXPECT_EQ(ErrorOf("Shape \"sph\\\nere\""),
              "<string>:1:7: error: unterminated string: expected a closing '\"' before the end "
              "of the line");
}

TEST(Tokenizer, ReportsBadEscapeAtTheBackslash) {
    EXPECT_EQ(ErrorOf("Shape \"a\\qb\""),
              "<string>:1:9: error: unknown escape sequence \"\\q\": expected one of \\b \\f \\n "
              "\\r \\t \\\\ \\' \\\"");
}

TEST(Tokenizer, ReportsUnexpectedCharacters) {
    EXPECT_EQ(ErrorOf("Translate 1, 2 3"),
              "<string>:1:12: error: unexpected character ',': expected a directive, a number, a "
              "quoted string, \"[\" or \"]\"");
    EXPECT_EQ(ErrorOf("\n  \x01"), "<string>:2:3: error: unexpected character byte 0x01: "
                                   "expected a directive, a number, a quoted string, \"[\" or "
                                   "\"]\"");
    const std::string expected =
        ": expected a directive, a number, a quoted string, \"[\" or \"]\"";
    EXPECT_EQ(ErrorOf("Shape {"), "<string>:1:7: error: unexpected character '{'" + expected);
    EXPECT_EQ(ErrorOf("Shape \x7f"), "<string>:1:7: error: unexpected character byte 0x7f" + expected);
    // UTF-8 outside strings: the first byte of the sequence is named.
    EXPECT_EQ(ErrorOf("Caf\xc3\xa9"), "<string>:1:4: error: unexpected character byte 0xc3" + expected);
}

TEST(Tokenizer, RejectsUtf16) {
    EXPECT_EQ(ErrorOf("\xff\xfeW\0"),
              "<string>:1:1: error: the file is encoded as UTF-16: expected UTF-8 or ASCII text");
    EXPECT_EQ(ErrorOf(std::string("\xfe\xff\0W", 4)),
              "<string>:1:1: error: the file is encoded as UTF-16: expected UTF-8 or ASCII text");
}

// Directives

TEST(Parser, DeliversEveryDirectiveWithItsLocation) {
    std::vector<std::string> calls = Parse(R"(Option "bool disablepixeljitter" true
Option "string seed" "7"
ColorSpace "srgb"
LookAt 0 0 5  0 0 0  0 1 0
Camera "perspective" "float fov" 45
Film "rgb"
Sampler "zsobol"
Integrator "path"
PixelFilter "gaussian"
Accelerator "bvh"
TransformTimes 0 1
ActiveTransform StartTime
ActiveTransform EndTime
ActiveTransform All
MakeNamedMedium "fog" "string type" "homogeneous"
WorldBegin
AttributeBegin
  Identity
  Translate 1 2 3
  Scale 2 2 2
  Rotate 90 0 0 1
  Transform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 ]
  ConcatTransform [ 2 0 0 0 0 2 0 0 0 0 2 0 0 0 0 1 ]
  CoordinateSystem "mine"
  CoordSysTransform "camera"
  Attribute "shape" "float radius" 2
  Texture "checks" "spectrum" "checkerboard" "float uscale" 4
  Material "diffuse"
  MakeNamedMaterial "red" "string type" "diffuse"
  NamedMaterial "red"
  MediumInterface "fog" ""
  MediumInterface "fog"
  LightSource "point"
  AreaLightSource "diffuse"
  ReverseOrientation
  Shape "sphere"
AttributeEnd
ObjectBegin "thing"
ObjectEnd
ObjectInstance "thing"
)");
    std::vector<std::string> expected = {
        "Option bool disablepixeljitter = true @<string>:1:1",
        "Option string seed = 7 @<string>:2:1",
        "ColorSpace srgb @<string>:3:1",
        "LookAt 0 0 5 0 0 0 0 1 0 @<string>:4:1",
        "Camera perspective \"float fov\" [ 45 ]@<string>:5:22 @<string>:5:1",
        "Film rgb @<string>:6:1",
        "Sampler zsobol @<string>:7:1",
        "Integrator path @<string>:8:1",
        "PixelFilter gaussian @<string>:9:1",
        "Accelerator bvh @<string>:10:1",
        "TransformTimes 0 1 @<string>:11:1",
        "ActiveTransformStartTime @<string>:12:1",
        "ActiveTransformEndTime @<string>:13:1",
        "ActiveTransformAll @<string>:14:1",
        "MakeNamedMedium fog \"string type\" [ \"homogeneous\" ]@<string>:15:23 @<string>:15:1",
        "WorldBegin @<string>:16:1",
        "AttributeBegin @<string>:17:1",
        "Identity @<string>:18:3",
        "Translate 1 2 3 @<string>:19:3",
        "Scale 2 2 2 @<string>:20:3",
        "Rotate 90 0 0 1 @<string>:21:3",
        "Transform 1 1 1 @<string>:22:3",
        "ConcatTransform 2 2 1 @<string>:23:3",
        "CoordinateSystem mine @<string>:24:3",
        "CoordSysTransform camera @<string>:25:3",
        "Attribute shape \"float radius\" [ 2 ]@<string>:26:21 @<string>:26:3",
        "Texture checks spectrum checkerboard \"float uscale\" [ 4 ]@<string>:27:46 "
        "@<string>:27:3",
        "Material diffuse @<string>:28:3",
        "MakeNamedMaterial red \"string type\" [ \"diffuse\" ]@<string>:29:27 @<string>:29:3",
        "NamedMaterial red @<string>:30:3",
        "MediumInterface fog  @<string>:31:3",
        "MediumInterface fog fog @<string>:32:3",
        "LightSource point @<string>:33:3",
        "AreaLightSource diffuse @<string>:34:3",
        "ReverseOrientation @<string>:35:3",
        "Shape sphere @<string>:36:3",
        "AttributeEnd @<string>:37:1",
        "ObjectBegin thing @<string>:38:1",
        "ObjectEnd @<string>:39:1",
        "ObjectInstance thing @<string>:40:1",
        "EndOfFiles"};
    EXPECT_EQ(calls, expected);
}

TEST(Parser, MediumInterfaceWithOneNameLeavesTheNextDirective) {
    EXPECT_EQ(Parse("MediumInterface \"fog\" WorldBegin"),
              (std::vector<std::string>{"MediumInterface fog fog @<string>:1:1",
                                        "WorldBegin @<string>:1:23", "EndOfFiles"}));
}

TEST(Parser, MediumInterfaceWithOneNameMayEndTheFile) {
    EXPECT_EQ(Parse("MediumInterface \"fog\""),
              (std::vector<std::string>{"MediumInterface fog fog @<string>:1:1", "EndOfFiles"}));
}

TEST(Parser, TransformBeginEndBecomeAttributeBlocksWithOneWarning) {
    Log().quiet = true;
    int before = Log().warnings;
    EXPECT_EQ(Parse("TransformBegin TransformEnd TransformBegin TransformEnd WorldEnd WorldEnd"),
              (std::vector<std::string>{"AttributeBegin @<string>:1:1",
                                        "AttributeEnd @<string>:1:16",
                                        "AttributeBegin @<string>:1:29",
                                        "AttributeEnd @<string>:1:44", "EndOfFiles"}));
    EXPECT_EQ(Log().warnings - before, 2);  // one for TransformBegin/End, one for WorldEnd
    Log().quiet = false;
}

TEST(Parser, WarningsAreLocated) {
    testing::internal::CaptureStderr();
    Parse("TransformBegin TransformEnd\nWorldEnd");
    EXPECT_EQ(testing::internal::GetCapturedStderr(),
              "<string>:1:1: warning: TransformBegin/TransformEnd are pbrt-v3 directives: treated "
              "as AttributeBegin/AttributeEnd\n"
              "<string>:2:1: warning: WorldEnd is a pbrt-v3 directive: ignored\n");
}

// Parameters

TEST(Parser, StoresValuesByTypeAndCanonicalizesAliases) {
    RecordingTarget target;
    ParseString(&target, R"(Shape "x"
        "integer a" [ -3 +4 ] "float b" 1.5 "point c" [1 2 3] "vector d" [0 0 1]
        "normal3 e" [0 1 0] "color f" [.5 .25 1] "bool g" [ true "false" ] "string h" "s"
        "texture i" "tex" "spectrum j" [300 1 800 2] "spectrum k" "metal-Au-eta"
        "blackbody l" 6500 "point2 m" [0 1] "vector2 n" [1 0] "bool o" false)");
    const ParsedParameterVector &p = target.lastParams;
    ASSERT_EQ(p.size(), 15u);
    EXPECT_EQ(p[0].type, "integer");
    EXPECT_EQ(p[0].numbers, (std::vector<double>{-3, 4}));
    EXPECT_EQ(p[1].numbers, (std::vector<double>{1.5}));
    EXPECT_EQ(p[2].type, "point3");
    EXPECT_EQ(p[3].type, "vector3");
    EXPECT_EQ(p[4].type, "normal");
    EXPECT_EQ(p[5].type, "rgb");
    EXPECT_EQ(p[5].numbers, (std::vector<double>{0.5, 0.25, 1}));
    EXPECT_EQ(p[6].bools, (std::vector<uint8_t>{1, 0}));
    EXPECT_EQ(p[7].strings, (std::vector<std::string>{"s"}));
    EXPECT_EQ(p[8].strings, (std::vector<std::string>{"tex"}));
    EXPECT_EQ(p[9].numbers, (std::vector<double>{300, 1, 800, 2}));
    EXPECT_EQ(p[10].strings, (std::vector<std::string>{"metal-Au-eta"}));
    EXPECT_EQ(p[11].numbers, (std::vector<double>{6500}));
    EXPECT_EQ(p[12].type, "point2");
    EXPECT_EQ(p[13].type, "vector2");
    EXPECT_EQ(p[14].bools, (std::vector<uint8_t>{0}));
    EXPECT_EQ(p[1].loc.ToString(), "<string>:2:31");
    EXPECT_EQ(p[14].ToString(), "\"bool o\" [ false ]");
}

TEST(Parser, BoolsMayBeQuoted) {
    RecordingTarget target;
    ParseString(&target, "Shape \"x\" \"bool b\" [ \"true\" false \"false\" true ]");
    ASSERT_EQ(target.lastParams.size(), 1u);
    EXPECT_EQ(target.lastParams[0].bools, (std::vector<uint8_t>{1, 0, 0, 1}));
}

TEST(Parser, ParameterListEndsAtTheNextDirective) {
    EXPECT_EQ(Parse("Shape \"sphere\" \"float radius\" 1 Shape \"disk\""),
              (std::vector<std::string>{
                  "Shape sphere \"float radius\" [ 1 ]@<string>:1:16 @<string>:1:1",
                  "Shape disk @<string>:1:33", "EndOfFiles"}));
}

TEST(Parser, RejectsValuesOfTheWrongKind) {
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" [ 1 \"x\" ]"),
              "<string>:1:25: error: unexpected \"x\": expected float values for \"float r\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" Shape"),
              "<string>:1:21: error: unexpected Shape: expected float values for \"float r\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"integer n\" [ 1.5 ]"),
              "<string>:1:25: error: unexpected 1.5: expected integer values for \"integer n\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"bool b\" 1"),
              "<string>:1:20: error: unexpected 1: expected bool values (true or false) for "
              "\"bool b\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"bool b\" \"yes\""),
              "<string>:1:20: error: unexpected \"yes\": expected bool values (true or false) for "
              "\"bool b\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"string f\" [ \"a\" 2 ]"),
              "<string>:1:28: error: unexpected 2: expected string values for \"string f\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"spectrum e\" [ \"a\" 2 ]"),
              "<string>:1:30: error: unexpected 2: expected string values for \"spectrum e\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"spectrum e\" [ 400 \"a\" ]"),
              "<string>:1:30: error: unexpected \"a\": expected float values for \"spectrum e\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"spectrum e\" true"),
              "<string>:1:24: error: unexpected true: expected float values or a quoted string "
              "for \"spectrum e\"");
}

TEST(Parser, RejectsNonFiniteAndOutOfRangeNumbers) {
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" [ nan ]"),
              "<string>:1:23: error: non-finite value nan for \"float r\": expected a finite "
              "number");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"rgb c\" [ 1 -inf 0 ]"),
              "<string>:1:23: error: non-finite value -inf for \"rgb c\": expected a finite "
              "number");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" 1e39"),
              "<string>:1:21: error: non-finite value 1e39 for \"float r\": expected a finite "
              "number");
    EXPECT_EQ(ErrorOf("Translate 0 1e999 0"),
              "<string>:1:13: error: non-finite value 1e999 for Translate: expected a finite "
              "number");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"integer n\" 2147483648"),
              "<string>:1:23: error: integer 2147483648 for \"integer n\" is out of range: "
              "expected a 32-bit integer");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"integer n\" -2147483649"),
              "<string>:1:23: error: integer -2147483649 for \"integer n\" is out of range: "
              "expected a 32-bit integer");
    // Beyond even 64 bits.
    EXPECT_EQ(ErrorOf("Shape \"s\" \"integer n\" 99999999999999999999"),
              "<string>:1:23: error: integer 99999999999999999999 for \"integer n\" is out of "
              "range: expected a 32-bit integer");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"integer n\" -2147483648"), "");
}

TEST(Parser, NumbersMayCarryOnePlusSign) {
    EXPECT_EQ(Parse("Translate +1 -2 +3.5 Shape \"s\" \"float r\" +0.5 \"integer n\" +7"),
              (std::vector<std::string>{
                  "Translate 1 -2 3 @<string>:1:1",
                  "Shape s \"float r\" [ 0.5 ]@<string>:1:32 \"integer n\" [ 7 ]@<string>:1:47 "
                  "@<string>:1:22",
                  "EndOfFiles"}));
    EXPECT_EQ(ErrorOf("Translate +-1 0 0"),
              "<string>:1:11: error: unexpected +-1: expected a number for Translate");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" ++1"),
              "<string>:1:21: error: unexpected ++1: expected float values for \"float r\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"integer n\" +"),
              "<string>:1:23: error: unexpected +: expected integer values for \"integer n\"");
}

TEST(Parser, RejectsValueCountsThatDoNotFitTheType) {
    EXPECT_EQ(ErrorOf("Shape \"s\" \"point3 P\" [ 1 2 3 4 ]"),
              "<string>:1:11: error: \"point3 P\" has 4 values: expected a multiple of 3");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"spectrum e\" [ 400 1 500 ]"),
              "<string>:1:11: error: \"spectrum e\" has 3 values: expected a multiple of 2");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" [ ]"),
              "<string>:1:11: error: \"float r\" has 0 values: expected at least one");
}

TEST(Parser, RejectsBadDeclarations) {
    EXPECT_EQ(ErrorOf("Shape \"s\" \"radius\" 1"),
              "<string>:1:11: error: bad parameter declaration \"radius\": expected \"type "
              "name\", such as \"float fov\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float a b\" 1"),
              "<string>:1:11: error: bad parameter declaration \"float a b\": expected \"type "
              "name\", such as \"float fov\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"flot r\" 1"),
              "<string>:1:11: error: unknown parameter type \"flot\" in \"flot r\": expected one "
              "of integer, float, point2, vector2, point3, vector3, normal, rgb, blackbody, "
              "spectrum, bool, string, texture");
}

// Syntax errors

TEST(Parser, RejectsUnknownDirectivesAndStrayTokens) {
    EXPECT_EQ(ErrorOf("WorldBegin\n  Shap \"sphere\""),
              "<string>:2:3: error: unknown directive \"Shap\"");
    EXPECT_EQ(ErrorOf("WorldBegin \"float r\" 1"),
              "<string>:1:12: error: unexpected \"float r\": expected a directive");
    EXPECT_EQ(ErrorOf("Translate 1 2 3 4"), "<string>:1:17: error: unexpected 4: expected a "
                                            "directive");
    EXPECT_EQ(ErrorOf("]"), "<string>:1:1: error: unexpected ]: expected a directive");
    EXPECT_EQ(ErrorOf("WorldBegin\n["), "<string>:2:1: error: unexpected [: expected a directive");
}

TEST(Parser, RejectsMissingOrMistypedDirectiveArguments) {
    EXPECT_EQ(ErrorOf("Shape sphere"),
              "<string>:1:7: error: unexpected sphere: expected a quoted string for Shape");
    EXPECT_EQ(ErrorOf("Translate 1 x 3"),
              "<string>:1:13: error: unexpected x: expected a number for Translate");
    EXPECT_EQ(ErrorOf("ActiveTransform Sometimes"),
              "<string>:1:17: error: unexpected Sometimes: expected All, StartTime or EndTime "
              "for ActiveTransform");
    EXPECT_EQ(ErrorOf("Transform 1 0 0 0"),
              "<string>:1:11: error: unexpected 1: expected \"[\" for Transform");
    EXPECT_EQ(ErrorOf("ConcatTransform [ 1 0 0 0 0 1 0 0 0 0 1 0 0 0 0 1 1 ]"),
              "<string>:1:51: error: unexpected 1: expected \"]\" after the 16 numbers of "
              "ConcatTransform");
    EXPECT_EQ(ErrorOf("Transform [ 1 0 0 ]"),
              "<string>:1:19: error: unexpected ]: expected a number for Transform");
}

TEST(Parser, ReportsPrematureEndOfFileWhereTheFileEnds) {
    EXPECT_EQ(ErrorOf("Texture \"t\" \"float\"\n"),
              "<string>:2:1: error: premature end of file: expected a quoted string for Texture");
    EXPECT_EQ(ErrorOf("LookAt 0 0 0"),
              "<string>:1:13: error: premature end of file: expected a number for LookAt");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\" [ 1"),
              "<string>:1:24: error: premature end of file: expected \"]\" closing the values of "
              "\"float r\"");
    EXPECT_EQ(ErrorOf("Shape \"s\" \"float r\""),
              "<string>:1:20: error: premature end of file: expected a value or \"[\" for "
              "\"float r\"");
    EXPECT_EQ(ErrorOf("Option \"bool x\""),
              "<string>:1:16: error: premature end of file: expected a value for Option");
}

TEST(Parser, ShortensLongTokensInMessages) {
    std::string longWord(60, 'a');
    EXPECT_EQ(ErrorOf("Shape " + longWord),
              "<string>:1:7: error: unexpected " + std::string(40, 'a') +
                  "...: expected a quoted string for Shape");
}

// Files and Include

TEST(Parser, IncludeResolvesAgainstTheMainFilesFolder) {
    RecordingTarget target;
    ParseFile(&target, std::string(PBRT_EXT_TEST_DATA_DIR) + "/parser/main.pbrt");
    std::string dir = std::string(PBRT_EXT_TEST_DATA_DIR) + "/parser/";
    EXPECT_EQ(target.calls,
              (std::vector<std::string>{
                  "WorldBegin @" + dir + "main.pbrt:2:1",
                  "Shape sphere @" + dir + "sub/part.pbrt:2:1",
                  "Shape disk @" + dir + "sub/deeper.pbrt:1:1",
                  "Shape cylinder @" + dir + "sub/part.pbrt:4:1",
                  "Shape sphere @" + dir + "sub/part.pbrt:2:1",
                  "Shape disk @" + dir + "sub/deeper.pbrt:1:1",
                  "Shape cylinder @" + dir + "sub/part.pbrt:4:1",
                  "AttributeEnd @" + dir + "main.pbrt:5:1", "EndOfFiles"}));
}

TEST(Parser, MissingFilesAreErrorsAtTheirReference) {
    EXPECT_EQ(FileErrorOf(kBad + "no_such_file.pbrt"),
              kBad + "no_such_file.pbrt: error: cannot open file: No such file or directory");
    EXPECT_EQ(ErrorOf("WorldBegin\nInclude \"no/such.pbrt\""),
              "<string>:2:1: error: cannot open included file \"no/such.pbrt\": No such file or "
              "directory");
    EXPECT_EQ(ErrorOf("Import \"" + kBad + "\""),
              "<string>:1:1: error: cannot open included file \"" + kBad + "\": Is a directory");
}

// A sysfs file reports a size of 4096 bytes and then reads fewer: the read itself fails.
TEST(Parser, ShortReadIsAnErrorAtTheReference) {
    const std::string path = "/sys/devices/system/cpu/online";
    if (!std::filesystem::is_regular_file(path))
        GTEST_SKIP() << path << " is not available";
    EXPECT_EQ(FileErrorOf(path), path + ": error: cannot open file: read error");
    EXPECT_EQ(ErrorOf("WorldBegin Include \"" + path + "\""),
              "<string>:1:12: error: cannot open included file \"" + path + "\": read error");
}

// Each file under tests/data/bad/parse_* and the exact error it must produce.
struct BadFile {
    const char *name;
    const char *error;  // after "<path>:"
};

constexpr BadFile kBadFiles[] = {
    {"parse_unknown_directive.pbrt", "4:5: error: unknown directive \"Shpae\""},
    {"parse_unterminated_string.pbrt",
     "3:7: error: unterminated string: expected a closing '\"' before the end of the line"},
    {"parse_bad_escape.pbrt",
     "2:40: error: unknown escape sequence \"\\x\": expected one of \\b \\f \\n \\r \\t \\\\ "
     "\\' \\\""},
    {"parse_unexpected_character.pbrt",
     "3:32: error: unexpected character ';': expected a directive, a number, a quoted string, "
     "\"[\" or \"]\""},
    {"parse_float_value.pbrt",
     "3:31: error: unexpected \"1\": expected float values for \"float radius\""},
    {"parse_nonfinite.pbrt",
     "5:7: error: non-finite value inf for \"point3 P\": expected a finite number"},
    {"parse_point_count.pbrt", "3:22: error: \"point3 P\" has 5 values: expected a multiple of 3"},
    {"parse_unknown_type.pbrt",
     "2:20: error: unknown parameter type \"colour\" in \"colour reflectance\": expected one of "
     "integer, float, point2, vector2, point3, vector3, normal, rgb, blackbody, spectrum, bool, "
     "string, texture"},
    {"parse_premature_eof.pbrt",
     "3:38: error: premature end of file: expected \"]\" closing the values of \"point3 P\""},
    {"parse_integer_value.pbrt",
     "1:38: error: unexpected 5.5: expected integer values for \"integer maxdepth\""},
    {"parse_stray_parameter.pbrt", "2:12: error: unexpected \"float fov\": expected a directive"},
};

TEST(Parser, BadFilesFailWithTheirExactMessage) {
    for (const BadFile &bad : kBadFiles) {
        SCOPED_TRACE(bad.name);
        EXPECT_EQ(FileErrorOf(kBad + bad.name), kBad + bad.name + ":" + bad.error);
    }
}

TEST(Parser, RecursiveIncludeStopsAtTheDepthLimit) {
    std::string file = kBad + "parse_recursive_include.pbrt";
    EXPECT_EQ(FileErrorOf(file),
              file + ":2:1: error: Include nesting deeper than 64 (recursive Include?)");
}

TEST(Parser, ArgumentsDoNotContinueIntoTheIncludingFile) {
    std::string file = kBad + "parse_include_split_directive.pbrt";
    EXPECT_EQ(FileErrorOf(file), kBad + "parse_split_part.pbrt:2:14: error: premature end of "
                                        "file: expected a number for Translate");
}

// Big meshes are most of a large scene's bytes; they must parse at memory speed, not per-token
// allocation speed.
// A mesh-sized list keeps every value (its speed is benchmarks/parser_bench.cpp's).
TEST(Parser, LargeParameterListsKeepEveryValue) {
    constexpr int kPoints = 300000;
    std::string text = "Shape \"trianglemesh\" \"point3 P\" [";
    text.reserve(kPoints * 3 * 10);
    for (int i = 0; i < kPoints; ++i)
        text += " 0.125 -1.5 " + std::to_string(i);
    text += " ]\n";
    RecordingTarget target;
    ParseString(&target, std::move(text));
    ASSERT_EQ(target.lastParams.size(), 1u);
    const std::vector<double> &numbers = target.lastParams[0].numbers;
    ASSERT_EQ(numbers.size(), size_t(3 * kPoints));
    for (int i = 0; i < kPoints; ++i) {
        ASSERT_EQ(numbers[3 * i], 0.125);
        ASSERT_EQ(numbers[3 * i + 1], -1.5);
        ASSERT_EQ(numbers[3 * i + 2], i);
    }
}

}  // namespace
}  // namespace pbrt
