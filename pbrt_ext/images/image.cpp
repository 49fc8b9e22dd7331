#include "pbrt_ext/images/image.h"

#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/error.h"

#include "pbrt_ext/images/exrfile.h"
#include "pbrt_ext/images/imagecodec.h"
#include "pbrt_ext/images/imageheaders.h"
#include "pbrt_ext/images/pngfile.h"
#include "pbrt_ext/images/stbfile.h"
#include "pbrt_ext/util/atomicfile.h"
#include "pbrt_ext/util/resourcelimits.h"

#include <ImfChannelList.h>
#include <ImfDoubleAttribute.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfStandardAttributes.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

#include <unistd.h>

namespace pbrt {

namespace {

std::string LowercaseExtension(const std::string &path) {
    std::string ext = std::filesystem::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

// The file channels that become R, G, B: named R/G/B channels where present (EXR may hold
// more, in any order), else a single gray channel replicated, else the first three.
std::array<int, 3> RGBChannelIndices(const ImageFileSpec &spec) {
    std::array<int, 3> idx = {-1, -1, -1};
    const char *names[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c)
        for (int i = 0; i < spec.nChannels; ++i)
            if (i < int(spec.channelNames.size()) && spec.channelNames[size_t(i)] == names[c]) idx[c] = i;
    if (idx[0] >= 0 && idx[1] >= 0 && idx[2] >= 0) return idx;
    // Gray, or gray and alpha.
    if (spec.nChannels < 3) return {0, 0, 0};
    return {0, 1, 2};
}

// The channel "A" of an R, G, B, A file where it is not 1 everywhere; -1 otherwise.
int NontrivialAlphaIndex(const ImageFileSpec &spec, const std::vector<float> &raw) {
    int index[4] = {-1, -1, -1, -1};
    const char *names[4] = {"R", "G", "B", "A"};
    for (int c = 0; c < 4; ++c)
        for (int i = 0; i < spec.nChannels && i < int(spec.channelNames.size()); ++i)
            if (spec.channelNames[size_t(i)] == names[c]) index[c] = i;
    if (std::find(std::begin(index), std::end(index), -1) != std::end(index)) return -1;
    for (size_t i = size_t(index[3]); i < raw.size(); i += size_t(spec.nChannels))
        if (raw[i] != 1) return index[3];
    return -1;
}

// The reader for the file: libpng and OpenEXR for their formats (by signature, whatever the
// extension), stb_image for the formats pbrt-v4 reads with it (by extension), OpenImageIO's
// module for the rest.
std::unique_ptr<ImageFileReader> OpenImageFile(const std::string &path) {
    switch (ImageFileFormatOf(path)) {
    case ImageFileFormat::PNG: return OpenPNGFile(path);
    case ImageFileFormat::EXR: return OpenEXRFile(path);
    default: return IsSTBImageExtension(LowercaseExtension(path)) ? OpenSTBFile(path) : GetImageCodec().Open(path);
    }
}

}  // namespace

bool IsEXRFilename(const std::string &path) { return LowercaseExtension(path) == ".exr"; }

std::optional<std::string> ImageWriteError(const std::string &path) {
    namespace fs = std::filesystem;
    const std::string extension = LowercaseExtension(path);
    if (extension.empty())
        return "\"" + path + "\" has no extension to choose an image format by (.exr, .pfm, .png, ...)";
    if (extension != ".exr" && extension != ".png" && extension != ".pfm") {
        try {
            if (!GetImageCodec().HasWriter(path))
                return "no image writer for \"" + extension + "\" (" + path + "): use .exr, .pfm, .png "
                       "or another format OpenImageIO writes";
        } catch (const std::runtime_error &e) {
            return std::string(e.what());
        }
    }
    return OutputFolderError(path);
}

std::optional<std::string> OutputFolderError(const std::string &path) {
    namespace fs = std::filesystem;
    fs::path folder = fs::path(path).parent_path();
    if (folder.empty()) folder = ".";
    std::error_code ec;
    if (!fs::is_directory(folder, ec))
        return "the folder \"" + folder.string() + "\" of " + path + " does not exist";
    if (::access(folder.c_str(), W_OK) != 0)
        return "the folder \"" + folder.string() + "\" of " + path + " is not writable";
    return std::nullopt;
}

const RGBColorSpace &Image::ColorSpace() const {
    return colorSpace ? *colorSpace : RGBColorSpace::sRGB();
}

Image::Image(Point2i res) : resolution(res) {
    if (res.x < 0 || res.y < 0)
        throw std::runtime_error("Image: negative resolution " + std::to_string(res.x) + "x" +
                                 std::to_string(res.y));
    pixels.assign(3 * size_t(res.x) * size_t(res.y), 0.f);
}

Float Image::LookupNearestChannel(Point2f st, int c, WrapMode2D wrapMode) const {
    Point2i p(int(st.x * resolution.x), int(st.y * resolution.y));
    return GetChannel(p, c, wrapMode);
}

RGB Image::LookupNearest(Point2f st, WrapMode2D wrapMode) const {
    Point2i p(int(st.x * resolution.x), int(st.y * resolution.y));
    return GetChannels(p, wrapMode);
}

Float Image::BilerpChannel(Point2f st, int c, WrapMode2D wrapMode) const {
    return Bilerp(st, wrapMode)[c];
}

RGB Image::Bilerp(Point2f st, WrapMode2D wrapMode) const {
    // Pixel centers sit at half-integers in continuous pixel coordinates.
    Float x = st.x * resolution.x - 0.5f, y = st.y * resolution.y - 0.5f;
    int xi = int(std::floor(x)), yi = int(std::floor(y));
    Float dx = x - xi, dy = y - yi;
    return ((1 - dx) * (1 - dy)) * GetChannels(Point2i(xi, yi), wrapMode) +
           (dx * (1 - dy)) * GetChannels(Point2i(xi + 1, yi), wrapMode) +
           ((1 - dx) * dy) * GetChannels(Point2i(xi, yi + 1), wrapMode) +
           (dx * dy) * GetChannels(Point2i(xi + 1, yi + 1), wrapMode);
}

std::vector<Float> Image::GetSamplingDistribution() const {
    std::vector<Float> f(size_t(resolution.x) * size_t(resolution.y));
    for (int y = 0; y < resolution.y; ++y)
        for (int x = 0; x < resolution.x; ++x)
            f[size_t(y) * resolution.x + x] = GetChannels(Point2i(x, y)).Average();
    return f;
}

Float Image::MeanChannel() const {
    double sum = 0;
    for (int y = 0; y < resolution.y; ++y)
        for (int x = 0; x < resolution.x; ++x)
            sum += GetChannels(Point2i(x, y)).Average();
    return Float(sum / (double(resolution.x) * resolution.y));
}

std::optional<ColorEncoding> ColorEncoding::Get(const std::string &name) {
    if (name == "linear") return Linear();
    if (name == "sRGB") return SRGB();
    // "gamma <g>" with nothing after the number.
    float g = 0;
    int consumed = 0;
    if (std::sscanf(name.c_str(), "gamma %f%n", &g, &consumed) == 1 &&
        consumed == int(name.size()) && g > 0 && std::isfinite(g))
        return Gamma(g);
    return {};
}

std::string ColorEncoding::ToString() const {
    switch (kind) {
    case Kind::SRGB: return "sRGB";
    case Kind::Gamma: return fmt::format("gamma {}", gamma);
    default: return "linear";
    }
}

namespace {

// Every channel of every pixel of a file as float.
struct RawImage {
    ImageFileSpec spec;
    std::vector<float> pixels;  // spec.nChannels per pixel, row-major
};

// The file's RawImage, after the checks that keep a corrupt or hostile header from allocating
// what it declares. The caller keeps, besides the file's floats, keptBytesPerChannel per channel
// and keptBytesPerPixel per pixel (the image's own RGB, or ReadEXRChannels' copies and its
// caller's share).
RawImage ReadRawImage(const std::string &path, uint64_t keptBytesPerChannel, uint64_t keptBytesPerPixel) {
    CheckDeclaredSizes(path);  // before a decoder allocates what a corrupt header declares
    std::unique_ptr<ImageFileReader> in;
    try {
        in = OpenImageFile(path);
    } catch (const std::runtime_error &e) {
        ThrowFileError(path, e.what());
    }
    const ImageFileSpec &spec = in->Spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.nChannels <= 0)
        ThrowFileError(path, "the image has no pixels");
    // read_image would fill every slice of a volume into a buffer sized for one.
    if (spec.depth > 1)
        ThrowFileError(path, fmt::format("the image is a volume of {} slices; expected a 2D image",
                                         spec.depth));
    // The header alone decides the size: the file's channels as floats while decoding, then
    // what the caller keeps.
    const uint64_t bytesPerPixel =
        uint64_t(spec.nChannels) * (sizeof(float) + keptBytesPerChannel) + keptBytesPerPixel;
    CheckMemory(FileLoc{path, 0, 0},
                fmt::format("the {} x {} image of {} channel{}", spec.width, spec.height,
                            spec.nChannels, spec.nChannels == 1 ? "" : "s"),
                SaturatingProduct({uint64_t(spec.width), uint64_t(spec.height), bytesPerPixel}));
    CheckMemory(FileLoc{path, 0, 0},
                fmt::format("decoding the {} x {} image", spec.width, spec.height),
                spec.decodeBufferBytes);

    RawImage raw{spec, std::vector<float>(size_t(spec.width) * size_t(spec.height) * size_t(spec.nChannels))};
    try {
        in->ReadPixels(raw.pixels.data());
    } catch (const std::runtime_error &e) {
        ThrowFileError(path, e.what());
    }
    return raw;
}

// The colour space an image file's header names: its EXR chromaticities, matched to a space we
// know as pbrt-v4 matches them; sRGB, with a warning as pbrt-v4 gives, for others.
const RGBColorSpace *ColorSpaceOf(const std::string &path, const ImageFileSpec &spec) {
    if (!spec.chromaticities)
        return nullptr;
    const std::array<float, 8> &c = *spec.chromaticities;
    if (const RGBColorSpace *cs = RGBColorSpace::Lookup(Chromaticity{c[0], c[1]}, Chromaticity{c[2], c[3]},
                                                        Chromaticity{c[4], c[5]}, Chromaticity{c[6], c[7]}))
        return cs;
    Warning("%s: its chromaticities r (%g, %g) g (%g, %g) b (%g, %g) w (%g, %g) are none of %s; "
            "read as sRGB",
            path.c_str(), c[0], c[1], c[2], c[3], c[4], c[5], c[6], c[7],
            RGBColorSpace::NamesList().c_str());
    return nullptr;
}

}  // namespace

EXRChannels ReadEXRChannels(const std::string &path, uint64_t keptBytesPerPixel) {
    if (ImageFileFormatOf(path) != ImageFileFormat::EXR)
        ThrowFileError(path, "not an OpenEXR file");
    // Its channels are copied out of the file's interleaved floats, one by one.
    RawImage raw = ReadRawImage(path, sizeof(float), keptBytesPerPixel);
    const ImageFileSpec &spec = raw.spec;
    EXRChannels contents{Point2i(spec.width, spec.height), {}, spec.stringAttributes};
    const size_t nPixels = size_t(spec.width) * size_t(spec.height), stride = size_t(spec.nChannels);
    for (size_t c = 0; c < stride; ++c) {
        std::vector<float> &values = contents.channels[spec.channelNames[c]];
        values.resize(nPixels);
        for (size_t i = 0; i < nPixels; ++i) values[i] = raw.pixels[i * stride + c];
    }
    return contents;
}

Image Image::Read(const std::string &path, ColorEncoding encoding, ImageChannels channels) {
    const RawImage rawImage = ReadRawImage(path, 0, Image::NChannels() * sizeof(float));
    const ImageFileSpec &spec = rawImage.spec;
    const std::vector<float> &raw = rawImage.pixels;

    // Integer pixels are display-encoded; float pixels are radiometric already.
    if (spec.isFloat) encoding = ColorEncoding::Linear();
    std::array<int, 3> channel = RGBChannelIndices(spec);
    if (channels == ImageChannels::AlphaOfRGBA)
        if (int a = NontrivialAlphaIndex(spec, raw); a >= 0) channel = {a, a, a};
    if (spec.is8Bit) {
        Image image;
        image.resolution = Point2i(spec.width, spec.height);
        image.KeepBytes(raw, spec.nChannels, channel, encoding);
        image.colorSpace = ColorSpaceOf(path, spec);
        return image;
    }
    Image image(Point2i(spec.width, spec.height));
    image.colorSpace = ColorSpaceOf(path, spec);
    for (int y = 0; y < spec.height; ++y)
        for (int x = 0; x < spec.width; ++x)
            for (int c = 0; c < 3; ++c) {
                Float v = raw[(size_t(y) * size_t(spec.width) + size_t(x)) * size_t(spec.nChannels) + size_t(channel[c])];
                image.SetChannel(Point2i(x, y), c, encoding.ToLinear(v));
            }
    return image;
}

void Image::KeepBytes(const std::vector<float> &raw, int nChannels, std::array<int, 3> channel,
                      ColorEncoding encoding) {
    SetByteEncoding(encoding);
    size_t n = size_t(resolution.x) * size_t(resolution.y), stride = size_t(nChannels);
    auto sample = [&](size_t i, int c) { return raw[i * stride + size_t(channel[c])]; };
    auto byteAt = [&](size_t i, int c) { return uint8_t(std::lround(sample(i, c) * 255)); };
    // Equal samples are equal bytes.
    bool gray = channel[0] == channel[1] && channel[1] == channel[2];
    for (size_t i = 0; i < n && gray; ++i) gray = sample(i, 0) == sample(i, 1) && sample(i, 1) == sample(i, 2);
    byteChannels = gray ? 1 : 3;
    bytes.resize(n * size_t(byteChannels));
    for (size_t i = 0; i < n; ++i)
        for (int c = 0; c < byteChannels; ++c) bytes[i * size_t(byteChannels) + size_t(c)] = byteAt(i, c);
}

void Image::SetByteEncoding(ColorEncoding encoding) {
    // The table holds exactly what decoding each sample would give.
    byteEncoding = encoding;
    for (int b = 0; b < 256; ++b) toLinear[size_t(b)] = encoding.ToLinear(float(b) / 255);
}

void Image::SetChannel(Point2i p, int c, Float value) {
    if (Is8Bit()) {
        pixels = DecodeBytes();
        bytes.clear();
    }
    pixels[3 * PixelIndex(p) + size_t(c)] = value;
}

void Image::Write(const std::string &path, const ImageMetadata &metadata,
                  const std::vector<ImageExtraChannel> &extraChannels) const {
    if (Empty()) ThrowFileError(path, "cannot write an image without pixels");
    const size_t nPixels = size_t(resolution.x) * size_t(resolution.y);
    for (const ImageExtraChannel &channel : extraChannels)
        if (channel.values.size() != nPixels)
            ThrowFileError(path, "channel \"" + channel.name + "\" has " +
                                     std::to_string(channel.values.size()) + " values for " +
                                     std::to_string(nPixels) + " pixels");
    if (IsEXRFilename(path))
        WriteFileAtomically(path, [&](const std::string &tmp) { WriteEXR(path, tmp, metadata, extraChannels); });
    else if (extraChannels.empty() && LowercaseExtension(path) == ".pfm")
        WriteFileAtomically(path, [&](const std::string &tmp) { WritePFM(tmp); });
    else if (extraChannels.empty())
        WriteFileAtomically(path, [&](const std::string &tmp) { Write8Bit(path, tmp); });
    else
        ThrowFileError(path, "only OpenEXR files keep channels besides R, G and B: use .exr");
}

void Image::WriteEXR(const std::string &path, const std::string &tmpPath, const ImageMetadata &metadata,
                     const std::vector<ImageExtraChannel> &extraChannels) const {
    // Without crop information the data window is the whole image at the origin.
    Bounds2i dataBounds = metadata.pixelBounds.value_or(Bounds2i(Point2i(0, 0), resolution));
    Point2i full = metadata.fullResolution.value_or(dataBounds.pMax);
    if (dataBounds.Diagonal() != Vector2i(resolution.x, resolution.y))
        ThrowFileError(path, "metadata pixelBounds do not match the image resolution");

    Imath::Box2i displayWindow(Imath::V2i(0, 0), Imath::V2i(full.x - 1, full.y - 1));
    Imath::Box2i dataWindow(Imath::V2i(dataBounds.pMin.x, dataBounds.pMin.y),
                            Imath::V2i(dataBounds.pMax.x - 1, dataBounds.pMax.y - 1));
    Imf::Header header(displayWindow, dataWindow, 1.f, Imath::V2f(0, 0), 1.f, Imf::INCREASING_Y,
                       Imf::ZIP_COMPRESSION);
    header.insert("samplesPerPixel", Imf::IntAttribute(metadata.samplesPerPixel));
    header.insert("renderTimeSeconds", Imf::DoubleAttribute(metadata.renderTimeSeconds));
    if (metadata.interrupted) {
        header.insert("interrupted", Imf::IntAttribute(1));
        header.insert("maxSamplesPerPixel", Imf::IntAttribute(metadata.maxSamplesPerPixel));
    }
    if (!metadata.scene.empty()) header.insert("scene", Imf::StringAttribute(metadata.scene));
    if (const RGBColorSpace *cs = metadata.colorSpace) {
        auto v = [](Chromaticity c) { return Imath::V2f(c.x, c.y); };
        Imf::addChromaticities(header, Imf::Chromaticities(v(cs->r), v(cs->g), v(cs->b), v(cs->w)));
        header.insert("colorSpace", Imf::StringAttribute(std::string(cs->Name())));
    }
    for (const auto &[key, value] : metadata.extra) {
        // Overwriting a standard attribute (e.g. "channels") would corrupt the file.
        if (header.find(key) != header.end())
            ThrowFileError(path, "metadata key \"" + key + "\" collides with an EXR header attribute");
        header.insert(key, Imf::StringAttribute(value));
    }
    const char *names[3] = {"R", "G", "B"};
    for (const char *name : names) header.channels().insert(name, Imf::Channel(Imf::FLOAT));

    // OpenEXR addresses the buffer by absolute data-window coordinates.
    std::vector<Float> scratch;
    const std::vector<Float> &rgb = FloatRGB(scratch);
    size_t xStride = 3 * sizeof(float), yStride = xStride * size_t(resolution.x);
    char *base = reinterpret_cast<char *>(const_cast<Float *>(rgb.data())) -
                 ptrdiff_t(dataBounds.pMin.x) * ptrdiff_t(xStride) -
                 ptrdiff_t(dataBounds.pMin.y) * ptrdiff_t(yStride);
    Imf::FrameBuffer frameBuffer;
    for (int c = 0; c < 3; ++c)
        frameBuffer.insert(names[c], Imf::Slice(Imf::FLOAT, base + c * sizeof(float), xStride, yStride));
    for (const ImageExtraChannel &channel : extraChannels) {
        if (header.channels().findChannel(channel.name))
            ThrowFileError(path, "channel \"" + channel.name + "\" is written twice");
        header.channels().insert(channel.name, Imf::Channel(Imf::FLOAT));
        char *extraBase = reinterpret_cast<char *>(const_cast<float *>(channel.values.data())) -
                          ptrdiff_t(dataBounds.pMin.x) * ptrdiff_t(sizeof(float)) -
                          ptrdiff_t(dataBounds.pMin.y) * ptrdiff_t(sizeof(float) * size_t(resolution.x));
        frameBuffer.insert(channel.name, Imf::Slice(Imf::FLOAT, extraBase, sizeof(float),
                                                    sizeof(float) * size_t(resolution.x)));
    }
    try {
        Imf::OutputFile file(tmpPath.c_str(), header);
        file.setFrameBuffer(frameBuffer);
        file.writePixels(resolution.y);
    } catch (const std::exception &e) {
        ThrowFileError(path, std::string("OpenEXR: ") + e.what());
    }
}

std::vector<Float> Image::DecodeBytes() const {
    std::vector<Float> rgb(3 * size_t(resolution.x) * size_t(resolution.y));
    for (int y = 0; y < resolution.y; ++y)
        for (int x = 0; x < resolution.x; ++x)
            for (int c = 0; c < 3; ++c) rgb[3 * PixelIndex(Point2i(x, y)) + size_t(c)] = GetChannel(Point2i(x, y), c);
    return rgb;
}

void Image::WritePFM(const std::string &tmpPath) const {
    std::vector<Float> scratch;
    const std::vector<Float> &rgb = FloatRGB(scratch);
    std::FILE *f = std::fopen(tmpPath.c_str(), "wb");
    if (!f) ThrowFileError(tmpPath, "cannot open for writing");
    bool ok = std::fprintf(f, "PF\n%d %d\n-1\n", resolution.x, resolution.y) > 0;
    std::vector<float> row(3 * size_t(resolution.x));
    for (int y = resolution.y - 1; y >= 0 && ok; --y) {  // PFM's first row is the bottom one
        std::copy_n(rgb.begin() + 3 * size_t(y) * resolution.x, row.size(), row.begin());
        static_assert(std::endian::native == std::endian::little, "PFM with scale -1 is little-endian");
        ok = std::fwrite(row.data(), sizeof(float), row.size(), f) == row.size();
    }
    if (std::fclose(f) != 0 || !ok) ThrowFileError(tmpPath, "cannot write the image");
}

void Image::Write8Bit(const std::string &path, const std::string &tmpPath) const {
    std::vector<Float> scratch;
    const std::vector<Float> &rgb = FloatRGB(scratch);
    std::vector<uint8_t> encoded(rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) encoded[i] = ColorEncoding::SRGB().ToByte(rgb[i]);
    try {
        if (LowercaseExtension(path) == ".png")
            WritePNG(tmpPath, resolution.x, resolution.y, encoded.data());
        else
            GetImageCodec().Write8Bit(path, tmpPath, resolution.x, resolution.y, encoded.data());
    } catch (const std::runtime_error &e) {
        ThrowFileError(path, e.what());
    }
}

}  // namespace pbrt
