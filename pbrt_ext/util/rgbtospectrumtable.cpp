#include "pbrt_ext/util/rgbtospectrumtable.h"

// The table cmd/rgb2spec_opt generates at build time (<build>/pbrt_ext/generated/
// rgbspectrum_srgb.cpp): the layer brightnesses as C++, the coefficients as the bytes of a binary
// file the assembler includes (.incbin), since 2.4 million floats as C++ text would take the
// compiler far longer to parse than the optimizer takes to find them.
namespace pbrt {
extern const float sRGBToSpectrumTable_ZNodes[RGBToSpectrumTable::res];
}  // namespace pbrt
extern "C" const pbrt::RGBToSpectrumTable::CoefficientArray pbrt_ext_sRGBToSpectrumTable_Data;

namespace pbrt {

const RGBToSpectrumTable &RGBToSpectrumTable::sRGB() {
    static const RGBToSpectrumTable table(sRGBToSpectrumTable_ZNodes,
                                          &pbrt_ext_sRGBToSpectrumTable_Data);
    return table;
}

}  // namespace pbrt
