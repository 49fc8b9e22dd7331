#include "pbrt_ext/spectra/rgbtospectrumtable.h"

// The tables cmd/rgb2spec_opt generates at build time (<build>/pbrt_ext/generated/
// rgbspectrum_<space>.cpp): the layer brightnesses as C++, the coefficients as the bytes of a
// binary file the assembler includes (.incbin), since 2.4 million floats as C++ text would take
// the compiler far longer to parse than the optimizer takes to find them.
#define PBRT_EXT_DECLARE_TABLE(symbol)                                                  \
    namespace pbrt {                                                                    \
    extern const float symbol##ToSpectrumTable_ZNodes[RGBToSpectrumTable::res];         \
    }                                                                                   \
    extern "C" const pbrt::RGBToSpectrumTable::CoefficientArray                        \
        pbrt_ext_##symbol##ToSpectrumTable_Data;
PBRT_EXT_DECLARE_TABLE(sRGB)
PBRT_EXT_DECLARE_TABLE(DCI_P3)
PBRT_EXT_DECLARE_TABLE(Rec2020)
PBRT_EXT_DECLARE_TABLE(ACES2065_1)
#undef PBRT_EXT_DECLARE_TABLE

namespace pbrt {

const RGBToSpectrumTable &RGBToSpectrumTable::sRGB() {
    static const RGBToSpectrumTable table(sRGBToSpectrumTable_ZNodes,
                                          &pbrt_ext_sRGBToSpectrumTable_Data);
    return table;
}

const RGBToSpectrumTable &RGBToSpectrumTable::DCI_P3() {
    static const RGBToSpectrumTable table(DCI_P3ToSpectrumTable_ZNodes,
                                          &pbrt_ext_DCI_P3ToSpectrumTable_Data);
    return table;
}

const RGBToSpectrumTable &RGBToSpectrumTable::Rec2020() {
    static const RGBToSpectrumTable table(Rec2020ToSpectrumTable_ZNodes,
                                          &pbrt_ext_Rec2020ToSpectrumTable_Data);
    return table;
}

const RGBToSpectrumTable &RGBToSpectrumTable::ACES2065_1() {
    static const RGBToSpectrumTable table(ACES2065_1ToSpectrumTable_ZNodes,
                                          &pbrt_ext_ACES2065_1ToSpectrumTable_Data);
    return table;
}

}  // namespace pbrt
