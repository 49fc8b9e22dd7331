#include "pbrt_ext/film/gbuffer.h"

#include "pbrt_ext/spectra/spectrum.h"
#include "pbrt_ext/util/ciedata.h"

#include <cmath>
#include <string>

namespace pbrt {

namespace {

// The sampled spectrum's XYZ: the Monte Carlo estimate of its inner products with the CIE
// matching functions over CIE_Y_integral (pbrt-v4's SampledSpectrum::ToXYZ).
XYZ ToXYZ(const SampledSpectrum &s, const SampledWavelengths &lambda) {
    SampledSpectrum v = SafeDiv(s, lambda.PDF());
    XYZ xyz(0, 0, 0);
    for (int i = 0; i < NSpectrumSamples; ++i) {
        xyz.X += Spectra::X()(lambda[i]) * v[i];
        xyz.Y += Spectra::Y()(lambda[i]) * v[i];
        xyz.Z += Spectra::Z()(lambda[i]) * v[i];
    }
    Float k = 1 / (NSpectrumSamples * CIE_Y_integral);
    return XYZ(xyz.X * k, xyz.Y * k, xyz.Z * k);
}

void Accumulate(double *sum, const auto &v, Float weight, int n) {
    for (int c = 0; c < n; ++c) sum[c] += double(weight) * double(v[c]);
}

}  // namespace

void GBufferChannels::Add(size_t pixel, RGB sensorRGB, Float weight, const VisibleSurface &surface,
                          const SampledWavelengths &lambda, const RGBColorSpace &colorSpace) {
    Pixel &px = pixels[pixel];
    px.gBufferWeight += weight;
    for (int c = 0; c < 3; ++c) px.variance[c].Add(sensorRGB[c]);
    Accumulate(px.p, surface.p, weight, 3);
    Accumulate(px.n, surface.n, weight, 3);
    Accumulate(px.ns, surface.ns, weight, 3);
    Accumulate(px.uv, surface.uv, weight, 2);
    px.dzdx += double(weight) * surface.dpdx.z;
    px.dzdy += double(weight) * surface.dpdy.z;
    RGB albedo = colorSpace.ToRGB(ToXYZ(surface.albedo * colorSpace.illuminant.Sample(lambda), lambda));
    Accumulate(px.albedo, albedo, weight, 3);
}

std::vector<ImageExtraChannel> GBufferChannels::Channels(std::span<const double> weightSums) const {
    const char *names[] = {"Albedo.R", "Albedo.G", "Albedo.B", "P.X", "P.Y", "P.Z", "dzdx", "dzdy",
                           "N.X", "N.Y", "N.Z", "Ns.X", "Ns.Y", "Ns.Z", "u", "v",
                           "Variance.R", "Variance.G", "Variance.B", "RelativeVariance.R",
                           "RelativeVariance.G", "RelativeVariance.B"};
    std::vector<ImageExtraChannel> channels;
    for (const char *name : names) channels.push_back({name, std::vector<float>(pixels.size())});
    auto unit = [](const double *v) {
        double length = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
        return length > 0 ? Vector3f(Float(v[0] / length), Float(v[1] / length), Float(v[2] / length))
                          : Vector3f(0, 0, 0);
    };
    for (size_t i = 0; i < pixels.size(); ++i) {
        const Pixel &px = pixels[i];
        double w = weightSums[i] != 0 ? 1 / weightSums[i] : 1;
        double g = px.gBufferWeight != 0 ? 1 / px.gBufferWeight : 1;
        Vector3f n = unit(px.n), ns = unit(px.ns);
        double values[] = {px.albedo[0] * w, px.albedo[1] * w, px.albedo[2] * w,
                           px.p[0] * g, px.p[1] * g, px.p[2] * g,
                           std::abs(px.dzdx * g), std::abs(px.dzdy * g), n.x, n.y, n.z, ns.x, ns.y, ns.z,
                           px.uv[0] * g, px.uv[1] * g,
                           px.variance[0].Variance(), px.variance[1].Variance(), px.variance[2].Variance(),
                           px.variance[0].RelativeVariance(), px.variance[1].RelativeVariance(),
                           px.variance[2].RelativeVariance()};
        for (size_t c = 0; c < channels.size(); ++c) channels[c].values[i] = float(values[c]);
    }
    return channels;
}

}  // namespace pbrt
