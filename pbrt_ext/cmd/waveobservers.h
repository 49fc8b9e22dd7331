// What the pbrt_ext command does with the image between waves (RenderOptions::afterWave), as
// pbrt-v4's options ask: --write-partial-images writes it, --mse-reference-image with
// --mse-reference-out appends "<samples per pixel> <MSE>" lines, --display-server streams it to
// tev (cmd/tevclient.h).
#pragma once

#include "pbrt_ext/cmd/commandline.h"
#include "pbrt_ext/cmd/tevclient.h"
#include "pbrt_ext/images/image.h"

#include <cstdio>
#include <memory>
#include <string>

namespace pbrt {

class Scene;

class WaveObservers {
  public:
    // Reads the MSE reference and opens its output file (std::runtime_error when either fails,
    // or the reference's resolution is not the film's pixel bounds'); connects to the display
    // server (a warning when it can't: the render goes on without it).
    WaveObservers(const CommandLine &cmd, const Scene &scene);
    ~WaveObservers();
    WaveObservers(const WaveObservers &) = delete;
    WaveObservers &operator=(const WaveObservers &) = delete;

    bool Any() const { return writePartialImages || mseOut || display; }
    // After a wave, every pixel at samplesPerPixel samples. A failure is a warning and ends that
    // observer's work; the render goes on.
    void AfterWave(int samplesPerPixel);
    // The final image to the display server.
    void AfterRender();

  private:
    void Display(const Image &image);
    const Scene &scene;
    bool writePartialImages = false;
    Image reference;
    std::FILE *mseOut = nullptr;
    std::string mseOutName;
    std::unique_ptr<TevClient> display;
    std::string displayName;
};

// The mean over pixels and channels of the squared difference; the images' resolutions match.
double MeanSquaredError(const Image &a, const Image &b);

}  // namespace pbrt
