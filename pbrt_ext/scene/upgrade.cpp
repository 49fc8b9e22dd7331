#include "pbrt_ext/scene/upgrade.h"

#include "pbrt_ext/util/error.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <optional>

namespace pbrt {

namespace {

ParsedParameter *Find(ParsedParameterVector &params, const std::string &name) {
    for (ParsedParameter &p : params)
        if (p.name == name) return &p;
    return nullptr;
}

// Removes the parameter; returns it, or none.
std::optional<ParsedParameter> Take(ParsedParameterVector &params, const std::string &name) {
    auto it = std::find_if(params.begin(), params.end(), [&](const ParsedParameter &p) { return p.name == name; });
    if (it == params.end()) return std::nullopt;
    ParsedParameter p = std::move(*it);
    params.erase(it);
    return p;
}

void Rename(ParsedParameterVector &params, const std::string &from, const std::string &to) {
    if (ParsedParameter *p = Find(params, from)) p->name = to;
}

ParsedParameter Number(const std::string &type, const std::string &name, double value, const FileLoc &loc) {
    ParsedParameter p;
    p.type = type;
    p.name = name;
    p.loc = loc;
    p.numbers = {value};
    return p;
}

ParsedParameter String(const std::string &type, const std::string &name, std::vector<std::string> values,
                       const FileLoc &loc) {
    ParsedParameter p;
    p.type = type;
    p.name = name;
    p.loc = loc;
    p.strings = std::move(values);
    return p;
}

// Sets a number parameter, replacing one of that name.
void Set(ParsedParameterVector &params, ParsedParameter p) {
    Take(params, p.name);
    params.push_back(std::move(p));
}

// The value of an "rgb" parameter whose three values are equal; none otherwise.
std::optional<double> ConstantRGB(const ParsedParameter &p) {
    if (p.type != "rgb" || p.numbers.size() != 3 || p.numbers[0] != p.numbers[1] || p.numbers[1] != p.numbers[2])
        return std::nullopt;
    return p.numbers[0];
}

// pbrt-v3's parameter dropped on the way to `material`: silently where it had the value pbrt-v4
// implies (returns true), with a warning where it meant something else.
bool DropIfConstant(ParsedParameterVector &params, const std::string &name, double value,
                    const std::string &material) {
    std::optional<ParsedParameter> p = Take(params, name);
    if (!p) return false;
    std::optional<double> v = ConstantRGB(*p);
    if (v && *v == value) return true;
    WarningAt(p->loc, "\"%s\" is dropped: the \"%s\" material has no such parameter",
              p->name.c_str(), material.c_str());
    return false;
}

// An RGB "scale" (or L, I) that is the same in every channel, folded into *scale; false when the
// parameter is there but not such an RGB.
bool FoldRGBScale(ParsedParameterVector &params, const std::string &name, double *scale) {
    ParsedParameter *p = Find(params, name);
    if (!p || p->type == "float") return true;
    std::optional<double> v = ConstantRGB(*p);
    if (!v) return false;
    *scale *= *v;
    Take(params, name);
    return true;
}

// pbrt-v3's blackbody was [temperature scale]; pbrt-v4's is the temperature, normalized.
void FoldBlackbody(ParsedParameterVector &params, const std::string &name, double *scale) {
    ParsedParameter *p = Find(params, name);
    if (!p || p->type != "blackbody" || p->numbers.size() != 2) return;
    *scale *= p->numbers[1];
    p->numbers.pop_back();
}

void IndexToEta(const std::string &material, ParsedParameterVector &params, const FileLoc &loc) {
    if (material != "glass" && material != "uber") return;
    if (!Find(params, "index")) return;
    if (Find(params, "eta"))
        throw ParseError(loc, "material \"" + material + "\" has both \"index\" and \"eta\"");
    Rename(params, "index", "eta");
}

// The common scale of a light: "scale" (float or constant RGB), blackbody scales and `extra`.
void SetLightScale(ParsedParameterVector &params, double scale, const FileLoc &loc) {
    if (scale == 1) return;
    if (std::optional<ParsedParameter> s = Take(params, "scale")) scale *= s->numbers.empty() ? 1 : s->numbers[0];
    params.push_back(Number("float", "scale", scale, loc));
}

}  // namespace

void UpgradePixelFilter(std::string &name, ParsedParameterVector &params, const FileLoc &) {
    Rename(params, "xwidth", "xradius");
    Rename(params, "ywidth", "yradius");
    if (name == "gaussian")
        if (std::optional<ParsedParameter> alpha = Take(params, "alpha"); alpha && !alpha->numbers.empty())
            params.push_back(Number("float", "sigma", 1 / std::sqrt(2 * alpha->numbers[0]), alpha->loc));
}

void UpgradeFilm(std::string &type, ParsedParameterVector &params, const FileLoc &) {
    if (type == "image") type = "rgb";
    Rename(params, "maxsampleluminance", "maxcomponentvalue");
    if (std::optional<ParsedParameter> s = Take(params, "scale"); s && !s->numbers.empty())
        params.push_back(Number("float", "iso", 100 * s->numbers[0], s->loc));
}

void UpgradeSampler(std::string &name, ParsedParameterVector &, const FileLoc &) {
    if (name == "lowdiscrepancy" || name == "02sequence") name = "paddedsobol";
    else if (name == "maxmindist") name = "pmj02bn";
    else if (name == "random") name = "independent";
}

void UpgradeIntegrator(std::string &name, ParsedParameterVector &params, const FileLoc &loc) {
    Take(params, "rrthreshold");
    if (name == "sppm") {
        Take(params, "imagewritefrequency");
        if (std::optional<ParsedParameter> n = Take(params, "numiterations"))
            WarningAt(n->loc, "sppm's \"numiterations\" is dropped: pbrt-v4 takes the iterations "
                              "from the Sampler's pixel samples");
    }
    if (ParsedParameter *s = Find(params, "lightsamplestrategy"); s && s->strings == std::vector<std::string>{"spatial"})
        s->strings = {"bvh"};
    if (name == "directlighting") {
        name = "path";
        Set(params, Number("integer", "maxdepth", 1, loc));
    } else if (name == "whitted") {
        name = "path";
    }
}

void UpgradeCamera(std::string &name, ParsedParameterVector &params, const FileLoc &loc) {
    if (name == "environment") {
        name = "spherical";
        Set(params, String("string", "mapping", {"equirectangular"}, loc));
    }
    if (name == "realistic") Take(params, "simpleweighting");
}

void UpgradeMedium(ParsedParameterVector &params, const FileLoc &) {
    if (ParsedParameter *type = Find(params, "type"); type && type->strings == std::vector<std::string>{"heterogeneous"})
        type->strings = {"uniformgrid"};
}

void UpgradeTexture(std::string &type, const std::string &texname, ParsedParameterVector &params,
                    const FileLoc &loc) {
    if (type == "color") type = "spectrum";
    if (texname == "scale") {
        if (type == "float") {
            Rename(params, "tex1", "tex");
            Rename(params, "tex2", "scale");
        } else {
            // One of the two must be a grey RGB: it becomes the float "scale".
            int constants = 0;
            for (ParsedParameter &p : params) {
                if (p.name != "tex1" && p.name != "tex2") continue;
                if (std::optional<double> v = ConstantRGB(p); v && constants++ == 0) {
                    p = Number("float", "scale", *v, p.loc);
                } else if (p.type == "rgb") {
                    throw ParseError(p.loc, "a \"scale\" texture's \"" + p.name + "\" is an RGB that "
                                            "pbrt-v4 can't take as its float scale: edit the file");
                } else {
                    p.name = "tex";
                }
            }
        }
    }
    if (texname == "imagemap") {
        if (std::optional<ParsedParameter> t = Take(params, "trilinear"); t && !t->bools.empty())
            params.push_back(String("string", "filter", {t->bools[0] ? "trilinear" : "bilinear"}, t->loc));
    }
    if (texname == "imagemap" || texname == "ptex") {
        if (std::optional<ParsedParameter> g = Take(params, "gamma")) {
            if (!g->bools.empty())
                params.push_back(String("string", "encoding", {g->bools[0] ? "sRGB" : "linear"}, g->loc));
            else if (!g->numbers.empty())
                params.push_back(String("string", "encoding", {fmt::format("gamma {}", g->numbers[0])}, g->loc));
        }
    }
    (void)loc;
}

void UpgradeMaterial(std::string &name, ParsedParameterVector &params, const FileLoc &loc) {
    IndexToEta(name, params, loc);
    Rename(params, "bumpmap", "displacement");
    if (name == "uber") {
        name = "coateddiffuse";
        if (DropIfConstant(params, "Ks", 0, name)) {
            name = "diffuse";
            Take(params, "eta");
            Take(params, "roughness");
        }
        DropIfConstant(params, "Kr", 0, name);
        DropIfConstant(params, "Kt", 0, name);
        Rename(params, "Kd", "reflectance");
        if (std::optional<ParsedParameter> opacity = Take(params, "opacity")) {
            std::optional<double> v = ConstantRGB(*opacity);
            if (!v || *v != 1)
                throw ParseError(opacity->loc, "a non-opaque \"opacity\" of the \"uber\" material has "
                                               "no pbrt-v4 equivalent: edit the file");
        }
    } else if (name == "mix" && !Find(params, "materials")) {  // a pbrt-v4 mix is left as it is
        if (std::optional<ParsedParameter> amount = Take(params, "amount")) {
            if (amount->type == "rgb" && amount->numbers.size() == 3) {
                double average = (amount->numbers[0] + amount->numbers[1] + amount->numbers[2]) / 3;
                if (!ConstantRGB(*amount))
                    WarningAt(amount->loc, "the RGB \"amount\" becomes its average %g", average);
                params.push_back(Number("float", "amount", average, amount->loc));
            } else if (amount->type == "float" || amount->type == "texture") {
                params.push_back(*amount);
            } else {
                throw ParseError(amount->loc, "a \"mix\" material's \"amount\" of type " + amount->type +
                                                  " has no scalar: edit the file");
            }
        }
        std::optional<ParsedParameter> m1 = Take(params, "namedmaterial1"), m2 = Take(params, "namedmaterial2");
        if (!m1 || !m2 || m1->strings.empty() || m2->strings.empty())
            throw ParseError(loc, "a pbrt-v3 \"mix\" material needs \"namedmaterial1\" and \"namedmaterial2\"");
        // pbrt-v4's amount weighs the second of "materials": the order swaps.
        params.push_back(String("string", "materials", {m2->strings[0], m1->strings[0]}, loc));
    } else if (name == "substrate") {
        name = "coateddiffuse";
        DropIfConstant(params, "Ks", 1, name);
        Rename(params, "Kd", "reflectance");
    } else if (name == "glass") {
        name = "dielectric";
        DropIfConstant(params, "Kr", 1, name);
        DropIfConstant(params, "Kt", 1, name);
    } else if (name == "plastic") {
        name = "coateddiffuse";
        if (DropIfConstant(params, "Ks", 0, name)) {
            name = "diffuse";
            Take(params, "roughness");
            Take(params, "eta");
        }
        Rename(params, "Kd", "reflectance");
    } else if (name == "fourier") {
        throw ParseError(loc, "the \"fourier\" material has no pbrt-v4 equivalent (pbrt-v4 has "
                              "\"measured\"): edit the file");
    } else if (name == "kdsubsurface") {
        name = "subsurface";
        Rename(params, "Kd", "reflectance");
    } else if (name == "matte") {
        name = "diffuse";
        Rename(params, "Kd", "reflectance");
        Take(params, "sigma");
    } else if (name == "metal") {
        name = "conductor";
        DropIfConstant(params, "Kr", 1, name);
    } else if (name == "translucent") {
        name = "diffusetransmission";
        Rename(params, "Kd", "transmittance");
        DropIfConstant(params, "reflect", 0, name);
        DropIfConstant(params, "transmit", 1, name);
        DropIfConstant(params, "Ks", 0, name);
        Take(params, "roughness");
    } else if (name == "mirror") {
        name = "conductor";
        DropIfConstant(params, "Kr", 0, name);
        Set(params, Number("float", "roughness", 0, loc));
        Set(params, String("spectrum", "eta", {"metal-Ag-eta"}, loc));
        Set(params, String("spectrum", "k", {"metal-Ag-k"}, loc));
    } else if (name == "disney") {
        name = "diffuse";
        Rename(params, "color", "reflectance");
    } else if (name == "hair") {
        Rename(params, "color", "reflectance");
    } else if (name.empty() || name == "none") {
        name = "interface";
    }
}

void UpgradeLight(std::string &name, ParsedParameterVector &params, const FileLoc &loc) {
    double scale = 1;
    if (!FoldRGBScale(params, "scale", &scale))
        throw ParseError(Find(params, "scale")->loc, "pbrt-v4's light \"scale\" is a float, and this "
                                                      "RGB is not grey: edit the file");
    Take(params, "samples");
    if (Find(params, "mapname")) {
        const char *radiance = name == "infinite" ? "L" : name == "projection" ? "I" : nullptr;
        if (radiance && !FoldRGBScale(params, radiance, &scale))
            throw ParseError(Find(params, radiance)->loc,
                             std::string("with \"mapname\", pbrt-v4 takes no coloured \"") + radiance +
                                 "\": edit the file");
        Rename(params, "mapname", "filename");
        if (ParsedParameter *f = Find(params, "filename")) f->type = "string";
    }
    FoldBlackbody(params, "I", &scale);
    FoldBlackbody(params, "L", &scale);
    SetLightScale(params, scale, loc);
}

void UpgradeAreaLight(std::string &name, ParsedParameterVector &params, const FileLoc &loc) {
    double scale = 1;
    if (!FoldRGBScale(params, "scale", &scale))
        throw ParseError(Find(params, "scale")->loc, "pbrt-v4's light \"scale\" is a float, and this "
                                                      "RGB is not grey: edit the file");
    FoldBlackbody(params, "L", &scale);
    if (name == "area") name = "diffuse";
    Take(params, "nsamples");
    SetLightScale(params, scale, loc);
}

void UpgradeShape(std::string &name, ParsedParameterVector &params, const FileLoc &loc) {
    if (name == "loopsubdiv") Rename(params, "nlevels", "levels");
    if (name == "trianglemesh" || name == "plymesh") {
        Take(params, "discarddegenerateUVs");
        if (ParsedParameter *alpha = Find(params, "shadowalpha"); alpha && alpha->type == "texture")
            Take(params, "shadowalpha");
    }
    if (name == "trianglemesh") {
        // pbrt-v3 took uv as floats, or as "st".
        for (const char *old : {"st", "uv"})
            if (ParsedParameter *p = Find(params, old); p && (p->type == "float" || p->name == "st")) {
                p->type = "point2";
                p->name = "uv";
                break;
            }
    }
    Rename(params, "Kd", "reflectance");
    (void)loc;
}

}  // namespace pbrt
