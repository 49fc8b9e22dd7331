// Film slices: renders of disjoint ranges of sample indices that merge into the image one render
// of all of them gives (issue 21: a frame or a reference spread over machines).
//
// A film's pixel is a ratio of sums: the filter-weighted sensor RGB over the weight, plus the
// splats over the samples per pixel. Sums of disjoint sample ranges add, so a slice keeps the
// sums, not the ratio, and a merge adds them. A slice is an EXR:
//   R, G, B                         its own image, viewable like any render;
//   sums.R, sums.G, sums.B, sums.weight   the film's sums (RGBFilm::PixelSums);
//   splats.R, splats.G, splats.B    the unscaled splats, where the integrator splats (bdpt,
//                                   lightpath);
// and string attributes: pbrt_ext.samples ("first:last"), pbrt_ext.seconds (render time), and
// the identity, pbrt_ext.scene / .sampler / .integrator / .film, which every slice of a merge
// must share. The sums are stored as 32-bit floats: a merged pixel differs from the single
// render's by float rounding (a relative 1e-7 per slice where the sums do not cancel).
#pragma once

#include "pbrt_ext/film/film.h"
#include "pbrt_ext/images/image.h"
#include "pbrt_ext/options.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/samplers/samplers.h"

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace pbrt {

// What must agree for slices to merge, as (name, value) in a fixed order: the scene file's
// contents (a hash), the sampler (its kind, samples per pixel, randomization and seed), the
// integrator and the overrides that change it, and the film (resolution, pixel bounds, filter,
// clamp, sensor and colour space).
using SliceIdentity = std::vector<std::pair<std::string, std::string>>;

// sceneText: the scene file's bytes; the sampler, integrator and film: the scene's.
SliceIdentity MakeSliceIdentity(const std::string &sceneText, const Sampler &sampler,
                                const IntegratorOptions &integrator, const RGBFilm &film,
                                const RenderOverrides &overrides);

struct FilmSlice {
    Point2i fullResolution;
    Bounds2i pixelBounds;
    SampleRange samples;
    double seconds = 0;  // render time (a merge's: the sum of its slices')
    SliceIdentity identity;
    std::string scene;  // the scene file as the command line named it (not part of the identity)
    SquareMatrix<3> outputRGBFromSensorRGB;
    const RGBColorSpace *colorSpace = &RGBColorSpace::sRGB();  // the film's output space
    // Per pixel of pixelBounds, row-major: 4 sums (R, G, B, weight), and 3 splat sums or none.
    std::vector<double> sums, splats;

    static FilmSlice FromFilm(const RGBFilm &film, SampleRange samples, double seconds,
                              SliceIdentity identity, std::string scene);
    // The image of these samples alone: what the film of their render gives.
    Image GetImage() const;
    // Atomically (no partial file). Throws std::runtime_error.
    void Write(const std::string &path) const;
    // Throws std::runtime_error("<path>: error: <what>") for a file that is not a slice.
    static FilmSlice Read(const std::string &path);
};

// Adds slices one at a time, so that a merge holds two slices in memory however many there are:
// the sum so far and the one being added. Add throws std::runtime_error, naming both files, for
// a slice of another render (identity or splats); Result, once every range is known, for ranges
// that overlap or leave a gap (the result would be no single render's).
class FilmSliceMerger {
  public:
    void Add(FilmSlice slice, std::string name);
    // The slice of the union of the samples added; throws std::invalid_argument if none were.
    FilmSlice Result() &&;

  private:
    std::optional<FilmSlice> merged;  // the sum so far
    std::vector<std::pair<SampleRange, std::string>> ranges;  // each slice's, with its name, in order added
};

// The same for slices at hand (names[i] is slices[i]'s file).
FilmSlice MergeFilmSlices(const std::vector<FilmSlice> &slices, const std::vector<std::string> &names);

// What reading a slice and merging it keep per pixel, besides the file's floats: the slice's
// sums and the merge's (7 doubles each).
constexpr uint64_t kSliceBytesPerPixel = 2 * 7 * sizeof(double);

}  // namespace pbrt
