// pbrt-v4's named spectra (src/pbrt/util/spectrum.cpp's GetNamedSpectrum): its own tables of
// glasses, metals and illuminants (namedspectradata.cpp), and the camera sensor responses
// (sensordata.cpp).
#include "pbrt_ext/spectra/namedspectradata.h"
#include "pbrt_ext/spectra/sensordata.h"
#include "pbrt_ext/spectra/spectrum.h"

#include <map>
#include <string>
#include <string_view>

namespace pbrt {

namespace {

// Each table as pbrt-v4 makes it (PiecewiseLinearSpectrum::FromInterleaved: extended to the
// visible range by its end values, illuminants scaled to luminance 1). Lights tabulate what they
// emit at 1 nm themselves.
const std::map<std::string_view, Spectrum> &NamedTables() {
    static const std::map<std::string_view, Spectrum> tables = [] {
        std::map<std::string_view, Spectrum> m;
        for (size_t i = 0; i < kNumNamedSpectrumTables; ++i) {
            const NamedSpectrumTable &t = kNamedSpectrumTables[i];
            m.emplace(t.name, Spectrum::PiecewiseLinear(t.interleaved, t.unitLuminance));
        }
        return m;
    }();
    return tables;
}

}  // namespace

std::string NamedSpectrumNames() {
    std::string s;
    for (size_t i = 0; i < kNumNamedSpectrumTables; ++i) s += std::string(kNamedSpectrumTables[i].name) + ", ";
    return s + SensorNames();
}

pstd::optional<Spectrum> GetNamedSpectrum(std::string_view name) {
    const std::map<std::string_view, Spectrum> &tables = NamedTables();
    if (auto it = tables.find(name); it != tables.end()) return it->second;
    return GetSensorResponse(name);
}

}  // namespace pbrt
