#include "pbrt_ext/cmd/waveobservers.h"

#include "pbrt_ext/scene.h"
#include "pbrt_ext/util/log.h"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace pbrt {

double MeanSquaredError(const Image &a, const Image &b) {
    const Point2i res = a.Resolution();
    double sum = 0;
    for (int y = 0; y < res.y; ++y)
        for (int x = 0; x < res.x; ++x)
            for (int c = 0; c < 3; ++c) {
                double d = double(a.GetChannel(Point2i(x, y), c)) - b.GetChannel(Point2i(x, y), c);
                sum += d * d;
            }
    return sum / (3.0 * res.x * res.y);
}

WaveObservers::WaveObservers(const CommandLine &cmd, const Scene &scene)
    : scene(scene), writePartialImages(cmd.writePartialImages) {
    // The command line's or the scene's Option "msereferenceimage" (the loader checked the pair).
    const std::string &referenceName = scene.options.mseReferenceImage;
    if (!referenceName.empty()) {
        reference = Image::Read(referenceName);
        Vector2i size = scene.film.PixelBounds().Diagonal();
        if (reference.Resolution() != Point2i(size.x, size.y))
            throw std::runtime_error(referenceName + ": error: the MSE reference image is " +
                                     std::to_string(reference.Resolution().x) + " x " +
                                     std::to_string(reference.Resolution().y) + " pixels; the render is " +
                                     std::to_string(size.x) + " x " + std::to_string(size.y));
        mseOutName = scene.options.mseReferenceOut;
        mseOut = std::fopen(mseOutName.c_str(), "w");
        if (!mseOut)
            throw std::runtime_error(mseOutName + ": error: the MSE output: cannot open for "
                                     "writing: " + std::strerror(errno));
    }
    if (!cmd.displayServer.empty()) {
        try {
            display = std::make_unique<TevClient>(cmd.displayServer);
            displayName = std::filesystem::path(scene.film.GetFilename()).filename().string();
        } catch (const std::runtime_error &e) {
            Warning("%s; rendering without it", e.what());
        }
    }
}

WaveObservers::~WaveObservers() {
    if (mseOut) std::fclose(mseOut);
}

void WaveObservers::Display(const Image &image) {
    if (!display) return;
    try {
        display->Show(displayName, image);
    } catch (const std::runtime_error &e) {
        Warning("%s; no more updates", e.what());
        display.reset();
    }
}

void WaveObservers::AfterWave(int samplesPerPixel) {
    if (writePartialImages) {
        try {
            ImageMetadata metadata;
            metadata.samplesPerPixel = samplesPerPixel;
            scene.film.WriteImage(metadata);
        } catch (const std::runtime_error &e) {
            Warning("--write-partial-images: %s; no more partial images", e.what());
            writePartialImages = false;
        }
    }
    if (!mseOut && !display) return;
    const Image image = scene.film.GetImage();
    if (mseOut && (std::fprintf(mseOut, "%d %.9g\n", samplesPerPixel, MeanSquaredError(image, reference)) < 0 ||
                   std::fflush(mseOut) != 0)) {
        Warning("--mse-reference-out: %s: cannot write: %s", mseOutName.c_str(), std::strerror(errno));
        std::fclose(mseOut);
        mseOut = nullptr;
    }
    Display(image);
}

void WaveObservers::AfterRender() {
    if (display) Display(scene.film.GetImage());
}

}  // namespace pbrt
