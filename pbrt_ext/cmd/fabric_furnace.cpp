// fabric_furnace: the white-furnace table of FabricBxDF (the paper's Fig. 2 as numbers).
//
// For roughness 0 ... 1 (the paper's exponent mapping) and both normalizations, prints the directional
// albedo a(wo) = ∫ f cos dωi by quadrature for wo at several angles from the normal, across and along a
// tangent thread, plus its peak over the sphere; writes the same numbers as CSV for plotting.
//
// Usage: fabric_furnace [out.csv]
#include "pbrt_ext/bxdfs/albedo.h"
#include "pbrt_ext/bxdfs/fabric_albedo.h"

#include <cstdio>
#include <fstream>
#include <iostream>

using namespace pbrt;

namespace {

constexpr Float kPolarDegrees[] = {0, 30, 60, 85};
struct Azimuth {
    const char *name;
    Float degrees;  // from the thread, which lies along dpdu (x)
};
constexpr Azimuth kAzimuths[] = {{"across", 90}, {"along", 0}};

Vector3f Outgoing(Float polarDegrees, Float azimuthDegrees) {
    Float theta = Radians(polarDegrees), phi = Radians(azimuthDegrees);
    return SphericalDirection(std::sin(theta), std::cos(theta), phi);
}

const char *Name(FabricNormalization norm) {
    return norm == FabricNormalization::Paper ? "paper" : "unitpeak";
}

void PrintHeader(FabricNormalization norm) {
    std::printf("\nnormalization %s: directional albedo a(wo), tangent thread along dpdu\n",
                Name(norm));
    std::printf("roughness    n |");
    for (Azimuth az : kAzimuths)
        for (Float polar : kPolarDegrees)
            std::printf(" %6s %2.0f", az.name, polar);
    std::printf("\n");
}

}  // namespace

int main(int argc, char **argv) {
    if (argc > 2) {
        std::fprintf(stderr, "usage: fabric_furnace [out.csv]\n");
        return 2;
    }
    std::ofstream csv;
    if (argc == 2) {
        csv.open(argv[1]);
        if (!csv) {
            std::fprintf(stderr, "fabric_furnace: cannot write '%s'\n", argv[1]);
            return 1;
        }
        csv << "normalization,roughness,n,azimuth,polar_deg,albedo\n";
    }
    for (FabricNormalization norm : {FabricNormalization::Paper, FabricNormalization::UnitPeak}) {
        PrintHeader(norm);
        for (int step = 0; step <= 10; ++step) {
            Float roughness = step / Float(10);
            FabricBxDF bxdf(SampledSpectrum(1), roughness, Vector3f(1, 0, 0), FabricSampling::Best,
                            norm);
            std::printf("%9.1f %4.0f |", roughness, bxdf.Exponent());
            for (Azimuth az : kAzimuths)
                for (Float polar : kPolarDegrees) {
                    double albedo =
                        FabricDirectionalAlbedo(bxdf, Outgoing(polar, az.degrees), 256);
                    std::printf(" %9.4f", albedo);
                    if (csv)
                        csv << Name(norm) << ',' << roughness << ',' << bxdf.Exponent() << ','
                            << az.name << ',' << polar << ',' << albedo << '\n';
                }
            std::printf("\n");
        }
    }
    std::printf("\nThe paper's normalization peaks at 2/pi = 0.6366 or below (cosine left out);\n"
                "unit peak reaches 1 at normal incidence for a tangent thread, never above.\n");
    if (csv)
        std::printf("wrote %s\n", argv[1]);
    return csv || argc < 2 ? 0 : 1;
}
