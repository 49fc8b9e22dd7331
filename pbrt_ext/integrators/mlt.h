// Metropolis light transport in primary sample space (pbrt-v4's MLTIntegrator; Kelemen et al.
// 2002, over Veach's bidirectional strategies as Hachisuka et al.'s multiplexed MLT, 2014).
//
// A path is made from a vector of uniform values (MLTSampler) by one bdpt strategy (s, t) of
// one depth, the strategy chosen by the values too, and weighted by its MIS weight times the
// number of strategies of that depth. Markov chains over those vectors visit paths in
// proportion to their luminance; each proposal and the current state are splatted where they
// land with the expected-value weights (Veach's "use of expected values"), so rejected
// proposals still count. The image is the splats times b / mutationsPerPixel, where b, the
// average luminance of a path, comes from bootstrap paths that also choose each chain's start.
//
// Camera subpaths start uniformly over the film's sample bounds (the pixels and the filter's
// reach past them), light subpaths splat over the whole film: t = 1 contributions scale by the
// full film's area over the sample bounds' (bdpt.h's crop scale). pbrt-v4 leaves that out, which
// makes its t = 1 contributions brighter by that ratio (1.6 % on a 256 x 256 film under the
// gaussian filter's 1.5-pixel radius).
//
// pbrt-v4's parameters: maxdepth, bootstrapsamples, chains, mutationsperpixel (--spp sets it),
// largestepprobability, sigma, regularize. A perspective camera only (its importance), as
// pbrt-v4. The chains are split evenly over the threads, each part adding its splats to sums of
// its own (24 bytes a pixel), which the film then adds in order: an image depends on the seed
// and the thread count only. Past 1 GiB of such sums (a large frame on many threads) the parts
// splat into the film's own sums, in whatever order the threads run.
#pragma once

#include "pbrt_ext/render.h"

namespace pbrt {

class Scene;

// Throws std::invalid_argument for a camera without importance, and std::runtime_error when no
// bootstrap path carries light.
RenderStatistics RenderMLT(Scene &scene, const RenderOptions &options);

}  // namespace pbrt
