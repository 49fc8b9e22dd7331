// Renders a scene through pbrt_ext::pbrt_ext: a furnace, a diffuse sphere of reflectance 0.5 that
// fills the view inside a uniform environment of radiance 1. Every pixel's expected value is 0.5 in
// each channel; exits 1 unless the image mean is within 0.02 of it (16 x 16 pixels x 64 samples:
// the wavelengths' noise in the mean is about 0.002).
#include <pbrt_ext/options.h>
#include <pbrt_ext/render.h>
#include <pbrt_ext/scene.h>
#include <pbrt_ext/scene/sceneloader.h>

#include <cmath>
#include <cstdio>
#include <exception>

int main(int argc, char **argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: library_consumer scene.pbrt\n");
        return 2;
    }
    try {
        pbrt::RenderOverrides overrides;
        overrides.quiet = true;
        std::unique_ptr<pbrt::Scene> scene = pbrt::LoadScene(argv[1], overrides);
        pbrt::RenderOptions options;
        options.quiet = true;
        pbrt::Render(*scene, options);
        pbrt::Point2i res = scene->film.FullResolution();
        double mean[3] = {0, 0, 0};
        for (int y = 0; y < res.y; ++y)
            for (int x = 0; x < res.x; ++x) {
                pbrt::RGB rgb = scene->film.GetPixelRGB(pbrt::Point2i(x, y));
                mean[0] += rgb.r;
                mean[1] += rgb.g;
                mean[2] += rgb.b;
            }
        std::printf("library_consumer: image mean");
        bool ok = true;
        for (double &m : mean) {
            m /= res.x * res.y;
            std::printf(" %.4f", m);
            ok = ok && std::abs(m - 0.5) < 0.02;
        }
        std::printf(" (expected 0.5)\n");
        if (!ok)
            return 1;
        return 0;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "library_consumer: %s\n", e.what());
        return 1;
    }
}
