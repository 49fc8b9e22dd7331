#include "pbrt_ext/bxdfs/measured.h"

#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/resourcelimits.h"
#include "pbrt_ext/util/tensorfile.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace pbrt {

namespace {

// The fields pbrt-v4 reads from an RGL file, as their shapes must be (pbrt-v4's checks, which
// RGL's files meet): per phi_i and theta_i a vndf and a luminance grid, and a spectra grid per
// wavelength as well, all of one size.
class Fields {
  public:
    Fields(const std::string &path) : path(path), fields(ReadTensorFile(path)) {}

    const TensorField &Get(const std::string &name, TensorField::Type type, size_t rank) const {
        auto it = fields.find(name);
        if (it == fields.end()) Fail(fmt::format("has no field \"{}\"", name));
        const TensorField &f = it->second;
        if (f.type != type || f.shape.size() != rank)
            Fail(fmt::format("field \"{}\" is not a {}-dimensional {} array", name, rank,
                             type == TensorField::Type::UInt8 ? "uint8" : "float32"));
        return f;
    }
    // A float32 field's values, all finite.
    std::vector<float> Floats(const std::string &name, size_t rank) const {
        std::span<const float> v = Get(name, TensorField::Type::Float32, rank).Floats();
        for (float x : v)
            if (!std::isfinite(x))
                Fail(fmt::format("field \"{}\" holds a value that is not finite", name));
        return {v.begin(), v.end()};
    }
    // A one-dimensional float32 field of increasing values (a grid's parameter).
    std::vector<float> Axis(const std::string &name) const {
        std::vector<float> v = Floats(name, 1);
        if (v.empty()) Fail(fmt::format("field \"{}\" is empty", name));
        for (size_t i = 1; i < v.size(); ++i)
            if (!(v[i] > v[i - 1])) Fail(fmt::format("field \"{}\" does not increase", name));
        return v;
    }
    void Expect(bool ok, const std::string &what) const {
        if (!ok) Fail(what);
    }
    [[noreturn]] void Fail(const std::string &what) const {
        ThrowFileError(path, "not an RGL measured BRDF: " + what);
    }

  private:
    std::string path;
    TensorFields fields;
};

std::string Shape(const TensorField &f) {
    std::string s;
    for (uint64_t n : f.shape) s += (s.empty() ? "" : " x ") + std::to_string(n);
    return s;
}

}  // namespace

std::shared_ptr<const MeasuredBxDFData> MeasuredBxDFData::Read(const std::string &path) {
    // What the file's size bounds: the file and its fields (ReadTensorFile checks those), the
    // copies of the tables, and the cumulative sums of the densities.
    if (std::optional<uint64_t> size = RegularFileSize(path, nullptr))
        CheckMemory(FileLoc{path, 0, 0}, "the measured BRDF's tables",
                    SaturatingProduct({*size, 6}));
    const Fields file(path);
    using Type = TensorField::Type;
    std::vector<float> phi_i = file.Axis("phi_i"), theta_i = file.Axis("theta_i");
    auto data = std::make_shared<MeasuredBxDFData>();
    data->filename = path;
    data->wavelengths = file.Axis("wavelengths");
    file.Get("description", Type::UInt8, 1);
    const TensorField &jacobian = file.Get("jacobian", Type::UInt8, 1);
    file.Expect(jacobian.shape[0] == 1, "field \"jacobian\" is not one value");

    const TensorField &ndf = file.Get("ndf", Type::Float32, 2),
                      &sigma = file.Get("sigma", Type::Float32, 2);
    const TensorField &vndf = file.Get("vndf", Type::Float32, 4);
    const TensorField &luminance = file.Get("luminance", Type::Float32, 4);
    const TensorField &spectra = file.Get("spectra", Type::Float32, 5);
    const uint64_t nPhi = phi_i.size(), nTheta = theta_i.size();
    file.Expect(vndf.shape[0] == nPhi && vndf.shape[1] == nTheta,
                "field \"vndf\" is " + Shape(vndf) + ", not per phi_i and theta_i");
    file.Expect(luminance.shape[0] == nPhi && luminance.shape[1] == nTheta,
                "field \"luminance\" is " + Shape(luminance) + ", not per phi_i and theta_i");
    file.Expect(
        spectra.shape[0] == nPhi && spectra.shape[1] == nTheta &&
            spectra.shape[2] == data->wavelengths.size(),
        "field \"spectra\" is " + Shape(spectra) + ", not per phi_i, theta_i and wavelength");
    file.Expect(luminance.shape[2] == spectra.shape[3] && luminance.shape[3] == spectra.shape[4],
                "fields \"luminance\" and \"spectra\" have grids of different sizes");
    for (const TensorField *f : {&ndf, &sigma, &vndf, &luminance, &spectra}) {
        uint64_t y = f->shape[f->shape.size() - 2], x = f->shape[f->shape.size() - 1];
        file.Expect(x >= 2 && y >= 2 && x <= 1u << 16 && y <= 1u << 16,
                    "a grid of " + Shape(*f) + " values; expected at least 2 x 2 per slice");
    }

    data->isotropic = nPhi <= 2;
    if (!data->isotropic) {
        // pbrt-v4 reads only files whose phi_i spans the whole circle.
        int reduction = int(std::rint(2 * Pi / (phi_i.back() - phi_i.front())));
        file.Expect(reduction == 1, fmt::format("its phi_i spans 1/{} of the circle; only whole "
                                                "circles are supported, as in pbrt-v4",
                                                reduction));
    }
    auto grid = [&](const TensorField &f, auto params, bool normalize,
                    const std::vector<float> &values) {
        using Table = PiecewiseLinear2D<int(std::tuple_size_v<decltype(params)>)>;
        int x = int(f.shape[f.shape.size() - 1]), y = int(f.shape[f.shape.size() - 2]);
        try {
            return Table(values.data(), x, y, std::move(params), normalize);
        } catch (const std::invalid_argument &e) {
            file.Fail(e.what());
        }
    };
    using Axes2 = std::array<std::vector<float>, 2>;
    using Axes3 = std::array<std::vector<float>, 3>;
    // A distribution of normals and its projected area are never negative.
    std::vector<float> ndfValues = file.Floats("ndf", 2), sigmaValues = file.Floats("sigma", 2);
    for (float v : ndfValues) file.Expect(v >= 0, "field \"ndf\" holds a negative value");
    for (float v : sigmaValues) file.Expect(v >= 0, "field \"sigma\" holds a negative value");
    data->ndf = grid(ndf, std::array<std::vector<float>, 0>{}, false, ndfValues);
    data->sigma = grid(sigma, std::array<std::vector<float>, 0>{}, false, sigmaValues);
    data->vndf = grid(vndf, Axes2{phi_i, theta_i}, true, file.Floats("vndf", 4));
    data->luminance = grid(luminance, Axes2{phi_i, theta_i}, true, file.Floats("luminance", 4));
    data->spectra =
        grid(spectra, Axes3{phi_i, theta_i, data->wavelengths}, false, file.Floats("spectra", 5));
    return data;
}

}  // namespace pbrt
