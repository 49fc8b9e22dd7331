// ParameterDictionary: typed lookups with defaults, the wrong-type and wrong-count errors at
// the parameter's location, spectra kept as descriptions, precedence between merged lists, and
// ReportUnused naming the first parameter nobody read.
#include "pbrt_ext/scene/paramdict.h"

#include <gtest/gtest.h>

#include <string>
#include <vector>

namespace pbrt {
namespace {

// A parameter as the parser would produce it, located at line `line` of "scene.pbrt".
ParsedParameter Param(const std::string &type, const std::string &name,
                      std::vector<double> numbers, int line = 1) {
    ParsedParameter p;
    p.type = type;
    p.name = name;
    p.loc = {"scene.pbrt", line, 3};
    p.numbers = std::move(numbers);
    return p;
}

ParsedParameter StringParam(const std::string &type, const std::string &name,
                            std::vector<std::string> strings, int line = 1) {
    ParsedParameter p = Param(type, name, {}, line);
    p.strings = std::move(strings);
    return p;
}

ParsedParameter BoolParam(const std::string &name, std::vector<uint8_t> bools) {
    ParsedParameter p = Param("bool", name, {});
    p.bools = std::move(bools);
    return p;
}

template <typename F>
std::string ErrorOf(F &&f) {
    try {
        f();
    } catch (const ParseError &e) {
        return e.what();
    }
    return "";
}

TEST(ParameterDictionary, ReturnsValuesOrDefaults) {
    ParameterDictionary dict({Param("float", "fov", {45}), Param("integer", "maxdepth", {7}),
                              BoolParam("regularize", {1}),
                              StringParam("string", "filename", {"out.exr"}),
                              Param("point2", "uv", {0.25, 0.5}), Param("point3", "from", {1, 2, 3}),
                              Param("vector3", "dir", {0, 0, -1}), Param("normal", "n", {0, 1, 0})});
    EXPECT_EQ(dict.GetOneFloat("fov", 90), 45);
    EXPECT_EQ(dict.GetOneInt("maxdepth", 5), 7);
    EXPECT_TRUE(dict.GetOneBool("regularize", false));
    EXPECT_EQ(dict.GetOneString("filename", "x"), "out.exr");
    EXPECT_EQ(dict.GetOnePoint2f("uv", {}), Point2f(0.25f, 0.5f));
    EXPECT_EQ(dict.GetOnePoint3f("from", {}), Point3f(1, 2, 3));
    EXPECT_EQ(dict.GetOneVector3f("dir", {}), Vector3f(0, 0, -1));
    EXPECT_EQ(dict.GetOneNormal3f("n", {}), Normal3f(0, 1, 0));
    EXPECT_EQ(dict.GetOneFloat("absent", 2.5f), 2.5f);
    EXPECT_EQ(dict.GetOneString("absent", "def"), "def");
    EXPECT_TRUE(dict.GetFloatArray("absent").empty());
    EXPECT_FALSE(dict.GetOneSpectrum("absent").has_value());
    EXPECT_EQ(dict.GetTexture("absent"), "");
    EXPECT_NO_THROW(dict.ReportUnused());
}

TEST(ParameterDictionary, ReturnsArrays) {
    ParameterDictionary dict(
        {Param("float", "f", {1, 2}), Param("integer", "indices", {0, 1, 2, 2, 3, 0}),
         Param("point2", "uv", {0, 0, 1, 1}), Param("point3", "P", {0, 0, 0, 1, 2, 3}),
         Param("vector3", "S", {1, 0, 0}), Param("normal", "N", {0, 0, 1, 0, 1, 0}),
         StringParam("string", "names", {"a", "b"})});
    EXPECT_EQ(dict.GetFloatArray("f"), (std::vector<Float>{1, 2}));
    EXPECT_EQ(dict.GetIntArray("indices"), (std::vector<int>{0, 1, 2, 2, 3, 0}));
    EXPECT_EQ(dict.GetPoint2fArray("uv"), (std::vector<Point2f>{{0, 0}, {1, 1}}));
    EXPECT_EQ(dict.GetPoint3fArray("P"), (std::vector<Point3f>{{0, 0, 0}, {1, 2, 3}}));
    EXPECT_EQ(dict.GetVector3fArray("S"), (std::vector<Vector3f>{{1, 0, 0}}));
    EXPECT_EQ(dict.GetNormal3fArray("N"), (std::vector<Normal3f>{{0, 0, 1}, {0, 1, 0}}));
    EXPECT_EQ(dict.GetStringArray("names"), (std::vector<std::string>{"a", "b"}));
    EXPECT_NO_THROW(dict.ReportUnused());
}

TEST(ParameterDictionary, WrongTypeIsAnErrorAtTheParameter) {
    ParameterDictionary dict({Param("float", "maxdepth", {5}, 4), Param("rgb", "Kd", {1, 1, 1}, 6)});
    EXPECT_EQ(ErrorOf([&] { dict.GetOneInt("maxdepth", 5); }),
              "scene.pbrt:4:3: error: parameter \"float maxdepth\" has the wrong type: expected "
              "\"integer maxdepth\"");
    EXPECT_EQ(ErrorOf([&] { dict.GetTexture("Kd"); }),
              "scene.pbrt:6:3: error: parameter \"rgb Kd\" has the wrong type: expected "
              "\"texture Kd\"");
    EXPECT_EQ(ErrorOf([&] { dict.GetOneSpectrum("maxdepth"); }),
              "scene.pbrt:4:3: error: parameter \"float maxdepth\" has the wrong type: expected "
              "\"rgb maxdepth\", \"spectrum maxdepth\" or \"blackbody maxdepth\"");
}

TEST(ParameterDictionary, WrongCountIsAnErrorAtTheParameter) {
    ParameterDictionary dict({Param("float", "fov", {45, 50}, 2), Param("point3", "P", {1, 2}, 3),
                              Param("point3", "from", {1, 2, 3, 4, 5, 6}, 5)});
    EXPECT_EQ(ErrorOf([&] { dict.GetOneFloat("fov", 90); }),
              "scene.pbrt:2:3: error: \"float fov\" has 2 values: expected one");
    EXPECT_EQ(ErrorOf([&] { dict.GetPoint3fArray("P"); }),
              "scene.pbrt:3:3: error: \"point3 P\" has 2 values: expected a multiple of 3");
    EXPECT_EQ(ErrorOf([&] { dict.GetOnePoint3f("from", {}); }),
              "scene.pbrt:5:3: error: \"point3 from\" has 6 values: expected 3");
    EXPECT_EQ(ErrorOf([&] { CheckValueCount(Param("rgb", "L", {}, 9)); }),
              "scene.pbrt:9:3: error: \"rgb L\" has 0 values: expected at least one");
    EXPECT_EQ(ErrorOf([&] { CheckValueCount(Param("normal", "N", {1}, 8)); }),
              "scene.pbrt:8:3: error: \"normal N\" has 1 value: expected a multiple of 3");
    // A type the table lacks (the parser rejects those first) needs only some value.
    EXPECT_EQ(ErrorOf([&] { CheckValueCount(Param("colour", "c", {1, 2}, 7)); }), "");
    EXPECT_EQ(ErrorOf([&] { CheckValueCount(Param("colour", "c", {}, 7)); }),
              "scene.pbrt:7:3: error: \"colour c\" has 0 values: expected at least one");
}

TEST(ParameterDictionary, SpectraStayDescriptions) {
    ParameterDictionary dict(
        {Param("rgb", "Kd", {0.5, 0.25, 1}), Param("blackbody", "L", {6500}),
         Param("spectrum", "eta", {400, 1.5, 700, 1.4}),
         StringParam("spectrum", "k", {"metal-Au-k"}),
         StringParam("spectrum", "I", {"spds/lamp.spd"})});
    std::optional<SpectrumParam> rgb = dict.GetOneSpectrum("Kd");
    ASSERT_TRUE(rgb.has_value());
    EXPECT_EQ(rgb->kind, SpectrumParamKind::RGB);
    EXPECT_EQ(rgb->values, (std::vector<double>{0.5, 0.25, 1}));
    EXPECT_EQ(rgb->loc.ToString(), "scene.pbrt:1:3");
    EXPECT_EQ(dict.GetOneSpectrum("L")->kind, SpectrumParamKind::Blackbody);
    EXPECT_EQ(dict.GetOneSpectrum("L")->values, (std::vector<double>{6500}));
    EXPECT_EQ(dict.GetOneSpectrum("eta")->kind, SpectrumParamKind::Samples);
    EXPECT_EQ(dict.GetOneSpectrum("eta")->values, (std::vector<double>{400, 1.5, 700, 1.4}));
    EXPECT_EQ(dict.GetOneSpectrum("k")->kind, SpectrumParamKind::Named);
    EXPECT_EQ(dict.GetOneSpectrum("k")->name, "metal-Au-k");
    EXPECT_EQ(dict.GetOneSpectrum("I")->kind, SpectrumParamKind::File);
    EXPECT_EQ(dict.GetOneSpectrum("I")->name, "spds/lamp.spd");
    EXPECT_EQ(rgb->ToString(),
              "[ SpectrumParam kind: rgb values: [ 0.5 0.25 1 ] name: \"\" loc: scene.pbrt:1:3 ]");
    EXPECT_NO_THROW(dict.ReportUnused());
}

TEST(ParameterDictionary, RejectsMalformedSpectra) {
    ParameterDictionary dict({Param("spectrum", "eta", {500, 1.5, 400, 1.4}, 2),
                              Param("blackbody", "L", {6500, 2}, 3),
                              StringParam("spectrum", "k", {"a", "b"}, 4)});
    EXPECT_EQ(ErrorOf([&] { dict.GetOneSpectrum("eta"); }),
              "scene.pbrt:2:3: error: \"spectrum eta\": wavelength 400 follows 500: expected "
              "increasing wavelengths");
    EXPECT_EQ(ErrorOf([&] { dict.GetOneSpectrum("L"); }),
              "scene.pbrt:3:3: error: \"blackbody L\" has 2 values: expected one");
    EXPECT_EQ(ErrorOf([&] { dict.GetOneSpectrum("k"); }),
              "scene.pbrt:4:3: error: \"spectrum k\" has 2 values: expected one");
}

TEST(ParameterDictionary, TextureNamesAndTypeQueries) {
    ParameterDictionary dict({StringParam("texture", "reflectance", {"checks"}, 7)});
    EXPECT_TRUE(dict.HasParameter("reflectance"));
    EXPECT_FALSE(dict.HasParameter("roughness"));
    EXPECT_EQ(dict.ParameterType("reflectance"), "texture");
    EXPECT_EQ(dict.ParameterType("roughness"), "");
    ASSERT_NE(dict.Loc("reflectance"), nullptr);
    EXPECT_EQ(dict.Loc("reflectance")->ToString(), "scene.pbrt:7:3");
    EXPECT_EQ(dict.Loc("roughness"), nullptr);
    EXPECT_EQ(dict.GetTexture("reflectance"), "checks");
    EXPECT_NO_THROW(dict.ReportUnused());
}

TEST(ParameterDictionary, ReportUnusedNamesTheFirstUnreadParameter) {
    ParameterDictionary dict({Param("float", "radius", {1}, 2), Param("float", "raduis", {2}, 3),
                              Param("integer", "n", {1}, 4)});
    dict.GetOneFloat("radius", 1);
    EXPECT_EQ(ErrorOf([&] { dict.ReportUnused(); }),
              "scene.pbrt:3:3: error: unused parameter \"float raduis\"");
    // Type queries do not count as use.
    dict.ParameterType("raduis");
    dict.HasParameter("raduis");
    EXPECT_NE(ErrorOf([&] { dict.ReportUnused(); }), "");
}

TEST(ParameterDictionary, LaterDuplicatesAndOwnParametersTakePrecedence) {
    // Within one list the last of two equal names wins and shadows the first.
    ParameterDictionary dict({Param("float", "radius", {1}, 2), Param("float", "radius", {2}, 3)});
    EXPECT_EQ(dict.GetOneFloat("radius", 0), 2);
    EXPECT_EQ(dict.Loc("radius")->line, 3);
    EXPECT_NO_THROW(dict.ReportUnused());

    // A shape's own parameters win over those of `Attribute "shape"`.
    ParameterDictionary merged({Param("float", "radius", {3}, 5)},
                               {Param("float", "radius", {4}, 1), Param("float", "zmax", {1}, 1)});
    EXPECT_EQ(merged.GetOneFloat("radius", 0), 3);
    EXPECT_EQ(merged.GetOneFloat("zmax", 0), 1);
    EXPECT_NO_THROW(merged.ReportUnused());
}

TEST(ParameterDictionary, CopiesTrackUseIndependently) {
    ParameterDictionary dict({Param("float", "fov", {45})});
    ParameterDictionary copy = dict;
    copy.GetOneFloat("fov", 0);
    EXPECT_NO_THROW(copy.ReportUnused());
    EXPECT_EQ(ErrorOf([&] { dict.ReportUnused(); }),
              "scene.pbrt:1:3: error: unused parameter \"float fov\"");
}

TEST(ParameterDictionary, TypeTableAndAliases) {
    EXPECT_EQ(CanonicalParameterType("point"), "point3");
    EXPECT_EQ(CanonicalParameterType("vector"), "vector3");
    EXPECT_EQ(CanonicalParameterType("normal3"), "normal");
    EXPECT_EQ(CanonicalParameterType("color"), "rgb");
    EXPECT_EQ(CanonicalParameterType("float"), "float");
    ASSERT_NE(LookupParameterType("point3"), nullptr);
    EXPECT_EQ(LookupParameterType("point3")->nPerItem, 3);
    EXPECT_EQ(LookupParameterType("point"), nullptr);
    EXPECT_EQ(ParameterDictionary({Param("float", "fov", {45})}).ToString(),
              "[ ParameterDictionary params: \"float fov\" [ 45 ] ]");
}

}  // namespace
}  // namespace pbrt
