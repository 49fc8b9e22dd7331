// pbrt-v4's --upgrade: pbrt-v3's directives rewritten as pbrt-v4's, with pbrt-v4's own rules
// (its FormattingParserTarget): renamed types (Film "image" -> "rgb", Material "matte" ->
// "diffuse", "plastic" -> "coateddiffuse", "glass" -> "dielectric", "metal" and "mirror" ->
// "conductor", ...), renamed parameters (Kd -> reflectance, index -> eta, mapname -> filename,
// xwidth -> xradius, ...), RGB scales and two-value blackbodies folded into a float scale, and
// pbrt-v3's parameters pbrt-v4 dropped removed. Each function rewrites one directive's type and
// parameters in place; what pbrt-v4 can't express is a ParseError at loc, and a parameter dropped
// although it meant something is a warning there.
#pragma once

#include "pbrt_ext/scene/parser.h"

#include <string>

namespace pbrt {

void UpgradePixelFilter(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeFilm(std::string &type, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeSampler(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeIntegrator(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeCamera(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeMedium(ParsedParameterVector &params, const FileLoc &loc);
// type: "float", "spectrum" or pbrt-v3's "color"; texname: the texture's class.
void UpgradeTexture(std::string &type, const std::string &texname, ParsedParameterVector &params,
                    const FileLoc &loc);
// name: a Material's type, or a MakeNamedMaterial's "string type".
void UpgradeMaterial(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeLight(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeAreaLight(std::string &name, ParsedParameterVector &params, const FileLoc &loc);
void UpgradeShape(std::string &name, ParsedParameterVector &params, const FileLoc &loc);

}  // namespace pbrt
