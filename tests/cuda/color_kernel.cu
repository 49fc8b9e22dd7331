// Compile check: color.h, rgbtospectrumtable.h (the look-up) and ciedata.h are GPU-clean.
#include "pbrt_ext/spectra/rgbtospectrumtable.h"
#include "pbrt_ext/util/ciedata.h"
#include "pbrt_ext/util/color.h"

using namespace pbrt;

__global__ void ColorKernel(const RGBToSpectrumTable *table, Float *out) {
    RGB rgb = RGB(0.2f, 0.5f, 0.7f) * 0.5f + RGB(0.1f, 0.1f, 0.1f) / 2.f - 0.01f;
    RGBSigmoidPolynomial s = (*table)(rgb);
    XYZ xyz = XYZ::FromxyY({0.3127f, 0.329f}) + XYZ(0.1f, 0.2f, 0.3f) * 2.f;
    CIESample c = CIEAt(550.f);
    out[0] = s(500.f) + s.MaxValue() + rgb[1] + rgb.MaxComponentValue();
    out[1] = xyz.xy().x + xyz[2] + c.y * c.d65 / CIE_D65_Y_integral + CIE_Y_integral;
}
