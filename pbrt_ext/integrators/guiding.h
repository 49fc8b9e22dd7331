// guidedpath's and guidedvolpath's render: learn, then render with what was learned (Müller et al. 2017, section 5).
// Training iterations of 1, 2, 4, ... samples per pixel each render with the SD-tree of the last
// (recording into the next), until they have taken half of the budget or the next would take
// more; the rest of the budget renders with the final tree, frozen. Every iteration's samples
// stay in the image: each is unbiased, so that their sum is (weighting them by sample count, not
// by inverse variance, which would estimate its weights from the same noisy images). Under a
// time limit, training stops at half of it.
// With --guiding-load there is no training: the image is rendered with the tree read, so sample
// slices are exact and merge (scripts/render-distributed trains once); --guiding-save writes the
// trained tree.
#pragma once

#include "pbrt_ext/render.h"

namespace pbrt {

class Scene;

// Throws std::runtime_error for a tree file that cannot be read or written.
RenderStatistics RenderGuided(Scene &scene, SampleRange samples, const RenderOptions &options);

}  // namespace pbrt
