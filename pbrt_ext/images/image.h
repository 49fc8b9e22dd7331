// RGB images and their files (pbrt-v4's util/image.h, reduced to what the renderer uses: three
// linear channels, pbrt-v4's wrap modes and lookups).
//
// Values are always linear. An image read from an 8-bit file keeps its bytes, one per pixel where
// the file is gray (or its three channels are equal everywhere), and turns them into linear
// values through a table of the file's encoding, as pbrt-v4 keeps them: a quarter to a twelfth of
// the memory of float RGB, and texture lookups that miss the cache that much less. Every other
// image is float RGB. Encodings apply only at the integer file boundary. Reading goes
// through libpng for PNG, OpenEXR for EXR (by the file's signature), stb_image for TGA, JPEG,
// BMP, GIF, PSD, PIC and HDR (images/stbfile.h) and OpenImageIO for the rest (integer formats such as PNG, JPEG, TGA are decoded with a ColorEncoding, sRGB unless the
// caller says otherwise; float formats such as EXR, PFM, HDR are taken as linear; color is never
// premultiplied by alpha, as pbrt-v4 reads it). Writing EXR goes through OpenEXR (32-bit float
// RGB with the metadata as header attributes), PNG through libpng as 8-bit sRGB, any other
// extension through OpenImageIO as 8-bit sRGB. OpenImageIO is a module loaded on first use
// (images/imagecodec.h). Files are written atomically (util/atomicfile.h): a failed or interrupted write never
// leaves a partial file. File errors throw std::runtime_error("<path>: error: <what>").
//
// This is a host type (the pixels live in a std::vector), like pbrt-v4's Image outside its GPU
// build.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/bounds.h"
#include "pbrt_ext/util/color.h"
#include "pbrt_ext/util/math.h"
#include "pbrt_ext/util/vecmath.h"

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pbrt {

class RGBColorSpace;

// The sRGB transfer function (IEC 61966-2-1), on [0, 1].
PBRT_CPU_GPU inline Float SRGBToLinear(Float v) {
    if (v <= 0.04045f) return v * (1 / 12.92f);
    return std::pow((v + 0.055f) * (1 / 1.055f), 2.4f);
}
PBRT_CPU_GPU inline Float LinearToSRGB(Float v) {
    if (v <= 0.0031308f) return 12.92f * v;
    return 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

// How integer pixel values map to linear ones (pbrt-v4's ColorEncoding: "linear", "sRGB",
// "gamma <g>"), applied to values already scaled to [0, 1].
class ColorEncoding {
  public:
    static ColorEncoding Linear() { return ColorEncoding(Kind::Linear, 1); }
    static ColorEncoding SRGB() { return ColorEncoding(Kind::SRGB, 1); }
    static ColorEncoding Gamma(Float gamma) { return ColorEncoding(Kind::Gamma, gamma); }
    // The encoding a scene file names; empty for an unknown name or a non-positive gamma.
    static std::optional<ColorEncoding> Get(const std::string &name);

    PBRT_CPU_GPU Float ToLinear(Float v) const {
        switch (kind) {
        case Kind::SRGB: return SRGBToLinear(v);
        case Kind::Gamma: return std::pow(v, gamma);
        default: return v;
        }
    }
    // The inverse: a linear value in [0, 1] to its encoded value in [0, 1].
    PBRT_CPU_GPU Float FromLinear(Float v) const {
        switch (kind) {
        case Kind::SRGB: return LinearToSRGB(v);
        case Kind::Gamma: return std::pow(v, 1 / gamma);
        default: return v;
        }
    }
    // The 8-bit code of a linear value, clamped to [0, 1] first (NaN becomes 0).
    uint8_t ToByte(Float v) const {
        v = v > 0 ? std::min<Float>(v, 1) : 0;
        return uint8_t(std::lround(FromLinear(v) * 255));
    }
    // The name Get() accepts, e.g. "gamma 2.2"; also a cache key.
    std::string ToString() const;
    friend bool operator==(const ColorEncoding &a, const ColorEncoding &b) {
        return a.kind == b.kind && a.gamma == b.gamma;
    }

  private:
    enum class Kind { Linear, SRGB, Gamma };
    ColorEncoding(Kind kind, Float gamma) : kind(kind), gamma(gamma) {}
    Kind kind;
    Float gamma;
};

// What a lookup outside the image sees (pbrt-v4's WrapMode). OctahedralSphere continues an
// equal-area octahedral environment map across its edges, which fold onto each other.
enum class WrapMode { Black, Clamp, Repeat, OctahedralSphere };

struct WrapMode2D {
    PBRT_CPU_GPU WrapMode2D(WrapMode w) : wrap{w, w} {}
    PBRT_CPU_GPU WrapMode2D(WrapMode x, WrapMode y) : wrap{x, y} {}
    WrapMode wrap[2];
};

// Moves *p into the image according to wrapMode; false when the pixel is outside and the mode
// is Black (the lookup is then zero). OctahedralSphere mirrors across the crossed edge and
// flips the other coordinate, as pbrt-v4 does, and must be used on both axes.
PBRT_CPU_GPU inline bool RemapPixelCoords(Point2i *p, Point2i resolution, WrapMode2D wrapMode) {
    if (wrapMode.wrap[0] == WrapMode::OctahedralSphere) {
        Point2i &q = *p;
        if (q.x < 0 || q.x >= resolution.x) {
            q.x = (q.x < 0) ? -q.x : 2 * resolution.x - 1 - q.x;
            q.y = resolution.y - 1 - q.y;
        }
        if (q.y < 0 || q.y >= resolution.y) {
            q.x = resolution.x - 1 - q.x;
            q.y = (q.y < 0) ? -q.y : 2 * resolution.y - 1 - q.y;
        }
        // A mirror of a one-pixel axis would land outside it.
        q.x = Clamp(q.x, 0, resolution.x - 1);
        q.y = Clamp(q.y, 0, resolution.y - 1);
        return true;
    }
    for (int c = 0; c < 2; ++c) {
        if ((*p)[c] >= 0 && (*p)[c] < resolution[c]) continue;
        switch (wrapMode.wrap[c]) {
        case WrapMode::Repeat:
            (*p)[c] = Mod((*p)[c], resolution[c]);
            break;
        case WrapMode::Clamp:
            (*p)[c] = Clamp((*p)[c], 0, resolution[c] - 1);
            break;
        default:  // Black
            return false;
        }
    }
    return true;
}

// Written as header attributes of an EXR (pbrt-v4's ImageMetadata, reduced). fullResolution
// and pixelBounds, when set, become the EXR display and data windows (a crop window renders a
// sub-rectangle of the full image).
struct ImageMetadata {
    int samplesPerPixel = 0;  // taken by every pixel
    double renderTimeSeconds = 0;
    // A render stopped early: some pixels hold up to maxSamplesPerPixel samples. Both become int
    // attributes ("interrupted" 1, "maxSamplesPerPixel") only then.
    bool interrupted = false;
    int maxSamplesPerPixel = 0;
    std::string scene;
    std::map<std::string, std::string> extra;
    std::optional<Point2i> fullResolution;
    std::optional<Bounds2i> pixelBounds;
    // The colour space of the pixels: the EXR's standard "chromaticities" attribute (primaries
    // and white point) and a "colorSpace" string attribute naming it. None when unset.
    const RGBColorSpace *colorSpace = nullptr;
};

enum class ImageChannels { RGB, AlphaOfRGBA };

// A float channel an EXR holds besides R, G and B: one value per pixel, row-major (a film
// slice's sums, filmslice.h).
struct ImageExtraChannel {
    std::string name;
    std::vector<float> values;
};

// Every channel of an EXR by name, and its string attributes.
struct EXRChannels {
    Point2i resolution;
    std::map<std::string, std::vector<float>> channels;  // one value per pixel, row-major
    std::map<std::string, std::string> stringAttributes;
};

// Whether Image::Write makes an EXR of path (by its extension, in any case): the only format it
// writes that keeps channels besides R, G and B.
bool IsEXRFilename(const std::string &path);

// Why Image::Write could not write path, for a check before the work that makes the image: no
// writer for its extension, or a folder that is missing or not writable. None when it can.
std::optional<std::string> ImageWriteError(const std::string &path);
// The folder part alone: path's folder is missing or not writable. None when it is.
std::optional<std::string> OutputFolderError(const std::string &path);

// keptBytesPerPixel: what the caller will make of each pixel, checked with the read against the
// memory budget (util/resourcelimits.h). Throws std::runtime_error("<path>: error: <what>"), also
// for a file that is not OpenEXR, or too large for the budget.
EXRChannels ReadEXRChannels(const std::string &path, uint64_t keptBytesPerPixel = 0);

class Image {
  public:
    static constexpr int NChannels() { return 3; }

    Image() = default;
    // Black; throws std::runtime_error for a negative resolution.
    explicit Image(Point2i resolution);

    Point2i Resolution() const { return resolution; }
    bool Empty() const { return resolution.x <= 0 || resolution.y <= 0; }

    // Pixel (0, 0) is the top-left corner of the file; c is 0 (red), 1 (green) or 2 (blue).
    Float GetChannel(Point2i p, int c, WrapMode2D wrapMode = WrapMode::Clamp) const {
        if (!RemapPixelCoords(&p, resolution, wrapMode)) return 0;
        size_t i = PixelIndex(p);
        if (!bytes.empty()) return toLinear[bytes[byteChannels == 1 ? i : 3 * i + size_t(c)]];
        return pixels[3 * i + size_t(c)];
    }
    RGB GetChannels(Point2i p, WrapMode2D wrapMode = WrapMode::Clamp) const {
        if (!RemapPixelCoords(&p, resolution, wrapMode)) return RGB(0, 0, 0);
        size_t i = PixelIndex(p);
        if (!bytes.empty()) {
            if (byteChannels == 1) {
                Float v = toLinear[bytes[i]];
                return RGB(v, v, v);
            }
            const uint8_t *b = &bytes[3 * i];
            return RGB(toLinear[b[0]], toLinear[b[1]], toLinear[b[2]]);
        }
        return RGB(pixels[3 * i], pixels[3 * i + 1], pixels[3 * i + 2]);
    }
    // An 8-bit image becomes float RGB first.
    void SetChannel(Point2i p, int c, Float value);
    // Whether the pixels are kept as the file's bytes (Read()).
    bool Is8Bit() const { return !bytes.empty(); }
    // The colour space of the RGB values: an EXR's "chromaticities" where Read() found them
    // (pbrt-v4's ImageMetadata::GetColorSpace), sRGB otherwise. Images made from this one
    // (resized, halved, re-encoded) keep it.
    const RGBColorSpace &ColorSpace() const;

    // Lookups at continuous coordinates st in [0, 1]^2 over the whole image (pixel centers at
    // half-integers, as pbrt-v4).
    Float LookupNearestChannel(Point2f st, int c, WrapMode2D wrapMode = WrapMode::Clamp) const;
    RGB LookupNearest(Point2f st, WrapMode2D wrapMode = WrapMode::Clamp) const;
    Float BilerpChannel(Point2f st, int c, WrapMode2D wrapMode = WrapMode::Clamp) const;
    RGB Bilerp(Point2f st, WrapMode2D wrapMode = WrapMode::Clamp) const;

    // The channel average per pixel, row-major (x fastest): the tabulated function that an
    // image light's PiecewiseConstant2D samples, as pbrt-v4's GetSamplingDistribution for an
    // equal-area parameterization.
    std::vector<Float> GetSamplingDistribution() const;
    // The mean of GetSamplingDistribution(): over all pixels, of their channels' average.
    Float MeanChannel() const;

    // pbrt-v4's resampling (images/imageresample.cpp). FloatResizeUp enlarges the image to
    // newResolution (no smaller on either axis) with a separable Lanczos filter of radius 2,
    // reading outside the image through wrapMode and clamping negative results to zero; the
    // result is float RGB. GeneratePyramid makes the levels of a MIPMap, finest first: the
    // image resized up to powers of two, then halved by averaging 2x2 texels down to 1x1. Each
    // level keeps the texel format of the image (an 8-bit image's levels are encoded back to
    // bytes with its encoding).
    Image FloatResizeUp(Point2i newResolution, WrapMode2D wrapMode) const;
    static std::vector<Image> GeneratePyramid(Image image, WrapMode2D wrapMode);

    // Integer formats are decoded with encoding; float formats are linear whatever it says.
    // AlphaOfRGBA reads an R, G, B, A file's alpha into all three channels, where it is not 1
    // everywhere (pbrt-v4's float image textures read alpha so), through the same encoding as
    // pbrt-v4 decodes it; any other file is read as RGB.
    static Image Read(const std::string &path, ColorEncoding encoding = ColorEncoding::SRGB(),
                      ImageChannels channels = ImageChannels::RGB);
    // extraChannels need an EXR path; each has a value per pixel.
    void Write(const std::string &path, const ImageMetadata &metadata = {},
               const std::vector<ImageExtraChannel> &extraChannels = {}) const;

  private:
    void WriteEXR(const std::string &path, const std::string &tmpPath, const ImageMetadata &metadata,
                  const std::vector<ImageExtraChannel> &extraChannels) const;
    void Write8Bit(const std::string &path, const std::string &tmpPath) const;
    // Portable float map: linear float RGB, bottom row first, little-endian (scale -1).
    void WritePFM(const std::string &tmpPath) const;
    // An 8-bit image's pixels as float RGB, row-major.
    std::vector<Float> DecodeBytes() const;
    // The pixels as float RGB: the image's own, or an 8-bit image's decoded into scratch.
    const std::vector<Float> &FloatRGB(std::vector<Float> &scratch) const {
        return Is8Bit() ? (scratch = DecodeBytes()) : pixels;
    }

    size_t PixelIndex(Point2i p) const { return size_t(p.y) * size_t(resolution.x) + size_t(p.x); }
    // The 8-bit samples of a file (raw: byte / 255 as the reader gives them, in its channel
    // layout) as this image's bytes, 1 channel where they are gray.
    void KeepBytes(const std::vector<float> &raw, int nChannels, std::array<int, 3> channel,
                   ColorEncoding encoding);
    // A float image's pixels as bytes of encoding, one channel per pixel or three.
    Image EncodedAs8Bit(ColorEncoding encoding, int channels) const;
    // The image as float RGB (an 8-bit image decoded).
    Image AsFloat() const;
    // A float image's pixel.
    void SetRGB(Point2i p, RGB v) {
        for (int c = 0; c < 3; ++c) pixels[3 * PixelIndex(p) + size_t(c)] = v[c];
    }
    // Bytes decode through encoding's table.
    void SetByteEncoding(ColorEncoding encoding);
    // Half the resolution (at least 1): each texel the average of the 2x2 texels it covers.
    Image HalfResolution() const;

    Point2i resolution{0, 0};
    std::vector<Float> pixels;        // float RGB, or empty for an 8-bit image
    std::vector<uint8_t> bytes;       // 8-bit: byteChannels per pixel
    int byteChannels = 0;
    std::array<Float, 256> toLinear{};  // 8-bit: the linear value of each byte
    ColorEncoding byteEncoding = ColorEncoding::Linear();  // 8-bit: what made toLinear
    const RGBColorSpace *colorSpace = nullptr;              // null: sRGB
};

}  // namespace pbrt
