// make_bsdf: writes an RGL .bsdf file (the format of pbrt-v4's measured material) made from
// pbrt-v4's rough conductor BRDF: Trowbridge-Reitz alpha and a metal's named eta and k spectra
// (materials/measuredwriter.h). scenes/measured.pbrt renders one beside the analytic conductor it
// was made from; the measured material's tests make their own.
//
// Usage: make_bsdf [--alpha A] [--metal NAME] [--resolution N] [--thetas N] [--lambda-step NM]
//                  out.bsdf
#include "pbrt_ext/materials/measuredwriter.h"
#include "pbrt_ext/spectra/spectrum.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>

using namespace pbrt;

int main(int argc, char **argv) {
    CLI::App app("Writes an RGL .bsdf file of pbrt-v4's rough conductor BRDF.");
    ConductorTableSpec spec;
    std::string metal = "Au", out;
    float lambdaStep = 10;
    app.add_option("--alpha", spec.alpha, "Trowbridge-Reitz alpha")->check(CLI::Range(0.01, 1.0));
    app.add_option("--metal", metal,
                   "pbrt-v4's metal-<NAME>-eta and -k spectra (Ag, Al, Au, Cu, "
                   "CuZn, MgO, TiO2)");
    app.add_option("--resolution", spec.resolution, "nodes per side of each table")
        ->check(CLI::Range(2, 256));
    app.add_option("--thetas", spec.thetaCount, "theta_i values")->check(CLI::Range(2, 256));
    app.add_option("--lambda-step", lambdaStep, "nm between wavelengths, 360-830 nm")
        ->check(CLI::Range(1.0, 470.0));
    app.add_option("out", out, "the .bsdf file to write")->required();
    CLI11_PARSE(app, argc, argv);

    auto eta = GetNamedSpectrum("metal-" + metal + "-eta");
    auto k = GetNamedSpectrum("metal-" + metal + "-k");
    if (!eta || !k) {
        std::fprintf(stderr, "make_bsdf: no named spectra metal-%s-eta and metal-%s-k\n",
                     metal.c_str(), metal.c_str());
        return 2;
    }
    spec.eta = *eta;
    spec.k = *k;
    for (float lambda = 360; lambda <= 830 + 1e-3f; lambda += lambdaStep)
        spec.wavelengths.push_back(lambda);
    try {
        WriteConductorBSDF(out, spec);
    } catch (const std::exception &e) {
        std::fprintf(stderr, "make_bsdf: %s\n", e.what());
        return 1;
    }
    return 0;
}
