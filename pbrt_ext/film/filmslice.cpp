#include "pbrt_ext/film/filmslice.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"
#include "pbrt_ext/util/hash.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>

namespace pbrt {

namespace {

constexpr const char *kSumChannels[4] = {"sums.R", "sums.G", "sums.B", "sums.weight"};
constexpr const char *kSplatChannels[3] = {"splats.R", "splats.G", "splats.B"};
constexpr const char *kAttributePrefix = "pbrt_ext.";
// What a film can be (create_options.cpp: pixel coordinates are floats) and a sampler can take.
constexpr int kMaxResolution = 1 << 24, kMaxSampleIndex = 1 << 30;

std::string MatrixString(const SquareMatrix<3> &m) {
    std::string s;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) s += fmt::format("{}{:.9g}", s.empty() ? "" : " ", m[i][j]);
    return s;
}

std::string FilmIdentity(const RGBFilm &film) {
    const Bounds2i b = film.PixelBounds();
    return fmt::format("resolution {} {} pixelbounds {} {} {} {} filter {} maxcomponentvalue {:.9g} "
                       "outputRGBFromSensorRGB {}",
                       film.FullResolution().x, film.FullResolution().y, b.pMin.x, b.pMin.y, b.pMax.x,
                       b.pMax.y, film.GetFilter().ToString(), film.MaxComponentValue(),
                       MatrixString(film.OutputRGBFromSensorRGB()));
}

// The guiding tree a guided render reads (its file's hash): slices with another tree differ.
std::string GuidingIdentity(const IntegratorOptions &i) {
    if (!IsGuided(i.type) || i.guiding.loadFile.empty())
        return "";
    std::ifstream in(i.guiding.loadFile, std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return fmt::format(" guiding-tree {:016x} bsdf-fraction {:.9g}",
                       MurmurHash64A(reinterpret_cast<const unsigned char *>(bytes.data()), bytes.size(), 0),
                       i.guiding.bsdfFraction);
}

std::string IntegratorIdentity(const IntegratorOptions &i, const RenderOverrides &o) {
    return fmt::format("type {} maxdepth {} strategy {} regularize {} spectralmis {} fabric-sampler {} "
                       "light-sampler {} layered-estimator {} displacement-edge-scale {:.9g}",
                       int(i.type), i.maxDepth, ToString(i.strategy), i.regularize, i.spectralMIS,
                       o.fabricSampler ? kFabricSamplingNames[int(*o.fabricSampler)] : "scene's",
                       o.lightSampler.value_or("scene's"), LayeredEstimatorName(o.layeredExitMIS),
                       o.displacementEdgeScale) +
           GuidingIdentity(i);
}

size_t PixelCount(const Bounds2i &b) { return size_t(b.Area()); }

// "<key>" of the file, which must be there.
const std::string &Attribute(const EXRChannels &exr, const std::string &path, const std::string &key) {
    auto it = exr.stringAttributes.find(kAttributePrefix + key);
    if (it == exr.stringAttributes.end())
        ThrowFileError(path, "not a film slice: no \"" + std::string(kAttributePrefix) + key +
                                 "\" attribute (render it with --samples)");
    return it->second;
}

// Exactly count finite numbers from text, separated by spaces or a ':' (a sample range).
std::vector<double> Numbers(const std::string &text, size_t count, const std::string &path,
                            const std::string &key) {
    std::string spaced = text;
    std::replace(spaced.begin(), spaced.end(), ':', ' ');
    std::istringstream in(spaced);
    std::vector<double> values;
    double v;
    while (in >> v) values.push_back(v);
    bool finite = std::all_of(values.begin(), values.end(), [](double x) { return std::isfinite(x); });
    if (values.size() != count || !in.eof() || !finite)
        ThrowFileError(path, fmt::format("attribute \"{}{}\" is \"{}\": expected {} numbers",
                                         kAttributePrefix, key, text, count));
    return values;
}

// Exactly count integers in [0, max] (pixel coordinates, sample indices).
std::vector<int> Integers(const std::string &text, size_t count, int max, const std::string &path,
                          const std::string &key) {
    std::vector<int> integers;
    for (double v : Numbers(text, count, path, key)) {
        if (v != std::floor(v) || v < 0 || v > max)
            ThrowFileError(path, fmt::format("attribute \"{}{}\" is \"{}\": expected integers "
                                             "from 0 to {}",
                                             kAttributePrefix, key, text, max));
        integers.push_back(int(v));
    }
    return integers;
}

// One channel's values into every stride-th element of out, from offset.
void Interleave(const EXRChannels &exr, const std::string &path, const char *name, size_t offset,
                size_t stride, std::vector<double> &out) {
    auto it = exr.channels.find(name);
    if (it == exr.channels.end())
        ThrowFileError(path, fmt::format("not a film slice: no channel \"{}\"", name));
    for (size_t i = 0; i < it->second.size(); ++i) out[i * stride + offset] = it->second[i];
}

std::vector<float> Deinterleave(const std::vector<double> &values, size_t offset, size_t stride) {
    std::vector<float> channel(values.size() / stride);
    for (size_t i = 0; i < channel.size(); ++i) channel[i] = float(values[i * stride + offset]);
    return channel;
}

std::string RangeString(SampleRange r) { return fmt::format("{}:{}", r.first, r.last); }

// Throws unless slice b may be merged with slice a.
void CheckSameRender(const FilmSlice &a, const std::string &nameA, const FilmSlice &b,
                     const std::string &nameB) {
    if (a.identity.size() != b.identity.size())
        throw std::runtime_error(fmt::format("merge: error: {} and {} describe their renders "
                                             "differently", nameA, nameB));
    for (size_t i = 0; i < a.identity.size(); ++i) {
        const auto &[field, valueA] = a.identity[i];
        const std::string &valueB = b.identity[i].second;
        if (field != b.identity[i].first || valueA != valueB)
            throw std::runtime_error(fmt::format(
                "merge: error: {} and {} are slices of different renders: their {} differs:\n"
                "  {}: {}\n  {}: {}",
                nameA, nameB, field, nameA, valueA, nameB, valueB));
    }
    if (a.splats.empty() != b.splats.empty())
        throw std::runtime_error(fmt::format("merge: error: {} has splats and {} has none",
                                             a.splats.empty() ? nameB : nameA,
                                             a.splats.empty() ? nameA : nameB));
}

}  // namespace

SliceIdentity MakeSliceIdentity(const std::string &sceneText, const Sampler &sampler,
                                const IntegratorOptions &integrator, const RGBFilm &film,
                                const RenderOverrides &overrides) {
    uint64_t hash = MurmurHash64A(reinterpret_cast<const unsigned char *>(sceneText.data()),
                                  sceneText.size(), 0);
    return {{"scene", fmt::format("{:016x}", hash)},
            {"sampler", sampler.ToString()},
            {"integrator", IntegratorIdentity(integrator, overrides)},
            {"film", FilmIdentity(film)}};
}

FilmSlice FilmSlice::FromFilm(const RGBFilm &film, SampleRange samples, double seconds,
                              SliceIdentity identity, std::string scene) {
    FilmSlice slice{film.FullResolution(), film.PixelBounds(), samples, seconds, std::move(identity),
                    std::move(scene), film.OutputRGBFromSensorRGB(), &film.ColorSpace(), {}, {}};
    const size_t n = PixelCount(slice.pixelBounds);
    slice.sums.resize(4 * n);
    if (film.HasSplats()) slice.splats.resize(3 * n);
    size_t i = 0;
    for (Point2i p : slice.pixelBounds) {
        RGBFilm::PixelSums s = film.GetPixelSums(p);
        for (int c = 0; c < 3; ++c) {
            slice.sums[4 * i + c] = s.rgb[c];
            if (!slice.splats.empty()) slice.splats[3 * i + c] = s.splat[c];
        }
        slice.sums[4 * i + 3] = s.weight;
        ++i;
    }
    return slice;
}

Image FilmSlice::GetImage() const {
    const Vector2i size = pixelBounds.Diagonal();
    Image image(Point2i(size.x, size.y));
    // The film's splat scale: one over the samples per pixel (render.cpp).
    const Float splatScale = Float(1.0 / samples.Count());
    for (int y = 0; y < size.y; ++y)
        for (int x = 0; x < size.x; ++x) {
            const size_t i = size_t(y) * size_t(size.x) + size_t(x);
            RGBFilm::PixelSums pixel;
            for (int c = 0; c < 3; ++c) {
                pixel.rgb[c] = sums[4 * i + c];
                if (!splats.empty()) pixel.splat[c] = splats[3 * i + c];
            }
            pixel.weight = sums[4 * i + 3];
            RGB rgb = pixel.ToOutputRGB(splatScale, outputRGBFromSensorRGB);
            for (int c = 0; c < 3; ++c) image.SetChannel(Point2i(x, y), c, rgb[c]);
        }
    return image;
}

void FilmSlice::Write(const std::string &path) const {
    ImageMetadata metadata;
    metadata.samplesPerPixel = samples.Count();
    metadata.renderTimeSeconds = seconds;
    metadata.scene = scene;
    metadata.fullResolution = fullResolution;
    metadata.pixelBounds = pixelBounds;
    metadata.colorSpace = colorSpace;
    auto set = [&](const std::string &key, std::string value) {
        metadata.extra[kAttributePrefix + key] = std::move(value);
    };
    set("samples", RangeString(samples));
    set("seconds", fmt::format("{:.17g}", seconds));
    set("fullResolution", fmt::format("{} {}", fullResolution.x, fullResolution.y));
    set("pixelBounds", fmt::format("{} {} {} {}", pixelBounds.pMin.x, pixelBounds.pMin.y,
                                   pixelBounds.pMax.x, pixelBounds.pMax.y));
    set("outputRGBFromSensorRGB", MatrixString(outputRGBFromSensorRGB));
    for (const auto &[name, value] : identity) set(name, value);

    std::vector<ImageExtraChannel> channels;
    for (size_t c = 0; c < 4; ++c) channels.push_back({kSumChannels[c], Deinterleave(sums, c, 4)});
    if (!splats.empty())
        for (size_t c = 0; c < 3; ++c) channels.push_back({kSplatChannels[c], Deinterleave(splats, c, 3)});
    GetImage().Write(path, metadata, channels);
}

FilmSlice FilmSlice::Read(const std::string &path) {
    const EXRChannels exr = ReadEXRChannels(path, kSliceBytesPerPixel);
    FilmSlice slice;
    std::vector<int> r = Integers(Attribute(exr, path, "samples"), 2, kMaxSampleIndex, path, "samples");
    slice.samples = {r[0], r[1]};
    if (slice.samples.Count() <= 0)
        ThrowFileError(path, "the sample range " + RangeString(slice.samples) + " is empty");
    slice.seconds = Numbers(Attribute(exr, path, "seconds"), 1, path, "seconds")[0];
    std::vector<int> f = Integers(Attribute(exr, path, "fullResolution"), 2, kMaxResolution, path,
                                  "fullResolution");
    slice.fullResolution = Point2i(f[0], f[1]);
    std::vector<int> b = Integers(Attribute(exr, path, "pixelBounds"), 4, kMaxResolution, path, "pixelBounds");
    slice.pixelBounds = Bounds2i(Point2i(b[0], b[1]), Point2i(b[2], b[3]));
    if (Intersect(slice.pixelBounds, Bounds2i(Point2i(0, 0), slice.fullResolution)) != slice.pixelBounds)
        ThrowFileError(path, "the pixelBounds attribute is not inside the fullResolution");
    Vector2i size = slice.pixelBounds.Diagonal();
    if (Point2i(size.x, size.y) != exr.resolution)
        ThrowFileError(path, "the pixelBounds attribute does not match the image's size");
    std::vector<double> m = Numbers(Attribute(exr, path, "outputRGBFromSensorRGB"), 9, path,
                                    "outputRGBFromSensorRGB");
    for (int i = 0; i < 9; ++i) slice.outputRGBFromSensorRGB[i / 3][i % 3] = Float(m[size_t(i)]);
    for (const char *name : {"scene", "sampler", "integrator", "film"})
        slice.identity.emplace_back(name, Attribute(exr, path, name));
    if (auto it = exr.stringAttributes.find("scene"); it != exr.stringAttributes.end())
        slice.scene = it->second;
    // The output space is also in the identity, through outputRGBFromSensorRGB.
    if (auto it = exr.stringAttributes.find("colorSpace"); it != exr.stringAttributes.end())
        if (const RGBColorSpace *cs = RGBColorSpace::GetNamed(it->second)) slice.colorSpace = cs;

    const size_t n = PixelCount(slice.pixelBounds);
    slice.sums.resize(4 * n);
    for (size_t c = 0; c < 4; ++c) Interleave(exr, path, kSumChannels[c], c, 4, slice.sums);
    if (exr.channels.count(kSplatChannels[0])) {
        slice.splats.resize(3 * n);
        for (size_t c = 0; c < 3; ++c) Interleave(exr, path, kSplatChannels[c], c, 3, slice.splats);
    }
    return slice;
}

void FilmSliceMerger::Add(FilmSlice slice, std::string name) {
    ranges.emplace_back(slice.samples, name);
    if (!merged) {
        merged = std::move(slice);
        return;
    }
    CheckSameRender(*merged, ranges.front().second, slice, name);
    for (size_t i = 0; i < merged->sums.size(); ++i) merged->sums[i] += slice.sums[i];
    for (size_t i = 0; i < merged->splats.size(); ++i) merged->splats[i] += slice.splats[i];
    merged->seconds += slice.seconds;
}

FilmSlice FilmSliceMerger::Result() && {
    if (!merged)
        throw std::invalid_argument("FilmSliceMerger: no slice to merge");
    // In sample order, to find overlaps and gaps between neighbours.
    std::sort(ranges.begin(), ranges.end(),
              [](const auto &a, const auto &b) { return a.first.first < b.first.first; });
    for (size_t k = 1; k < ranges.size(); ++k) {
        const auto &[prev, prevName] = ranges[k - 1];
        const auto &[next, nextName] = ranges[k];
        if (next.first < prev.last)
            throw std::runtime_error(fmt::format(
                "merge: error: {} (samples {}) and {} (samples {}) overlap: each sample must be "
                "merged once",
                prevName, RangeString(prev), nextName, RangeString(next)));
        if (next.first > prev.last)
            throw std::runtime_error(fmt::format(
                "merge: error: samples {}:{} are missing between {} and {}: the merge would be no "
                "single render's",
                prev.last, next.first, prevName, nextName));
    }
    FilmSlice result = std::move(*merged);
    result.samples = {ranges.front().first.first, ranges.back().first.last};
    return result;
}

FilmSlice MergeFilmSlices(const std::vector<FilmSlice> &slices, const std::vector<std::string> &names) {
    if (names.size() != slices.size())
        throw std::invalid_argument("MergeFilmSlices: one name per slice");
    FilmSliceMerger merger;
    for (size_t i = 0; i < slices.size(); ++i) merger.Add(slices[i], names[i]);
    return std::move(merger).Result();
}

}  // namespace pbrt
