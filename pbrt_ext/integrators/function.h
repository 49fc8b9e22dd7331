// pbrt-v4's FunctionIntegrator ("function"): how well a sample generator integrates, without a
// scene. Each pixel is an independent estimate of the integral over [0, 1)^2 of a test function
// whose integral is 1, from the sampler's first two dimensions (the pixel sample); after each
// sample index, the mean squared error of the estimates over the pixels is a row of the table
// written to "filename": "<samples> <mse>" per line. pbrt-v4's test functions and its
// treatment of each sampler: 2D Halton and Sobol' points randomized per pixel in the halton and
// paddedsobol samplers' ways (without the padded sampler's permutation of indices, so that the
// first 2^k points are a net), a fresh jittered grid of n samples for the stratified sampler at
// each n, the sampler's own pixel samples otherwise; "sobol" is refused (its pixel samples are one global sequence; paddedsobol
// is the per-pixel one). With "skipbad" (the default), rows are written only at counts where
// a sampler's points are well distributed (squares for stratified, powers of 2 for paddedsobol,
// 2^k 3^k for halton).
#pragma once

#include "pbrt_ext/options.h"
#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/util/vecmath.h"

#include <string>
#include <utility>
#include <vector>

namespace pbrt {

class Scene;

// The function at p in [0, 1)^2; each integrates to 1 there.
double EvaluateTestFunction(TestFunction f, Point2f p);

// The rows (samples per pixel, mean squared error over the pixels) of the scene's function
// integrator at its sampler's sample count, its pixels in parallel.
std::vector<std::pair<int, double>> FunctionErrorTable(const Scene &scene, const RenderOptions &options);

// Writes the table to the integrator's file, and the function's image if it asks for one.
// Throws std::runtime_error when a file cannot be written.
RenderStatistics RenderFunction(Scene &scene, const RenderOptions &options);

}  // namespace pbrt
