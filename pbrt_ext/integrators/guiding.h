// guidedpath's and guidedvolpath's render: learn, then render with what was learned (Müller et al. 2017, section 5).
// Training iterations of 1, 2, 4, ... samples per pixel each render with the SD-tree of the last
// (recording into the next), until they have taken half of the budget or the next would take
// more; the rest of the budget renders with the final tree, frozen. Every iteration's samples
// stay in the image, each render weighted by the inverse of its variance (inversevariance.h):
// an iteration guided by a young tree counts less than the last. Under a time limit, training
// stops at half of it.
// Guiding switches itself off where it costs more than it gains (the Cornell box: a guided
// sample costs some 1.8 times a path-traced one, and the guide lowers the variance little). A
// trial takes the place of the third training iteration, after 3 samples per pixel: of its 4,
// the first 2 sample with the tree learned so far (frozen) and the other 2 without guiding (path,
// or volpath where guidedvolpath renders media). It compares the two by relative variance
// (samplemoments.h) times cost, in rays, a guided ray weighing what the training and rendering
// still to come cost per ray (fixed measured factors: counted, not timed, so that a seed gives
// one image). The trial takes the path tracer's (or volpath's) variance from the guided samples,
// each estimating its second moment by importance weights (unguidedmoment.h): where rare bright
// paths carry the light, the path tracer's own few samples per pixel seldom find them and
// underestimate its variance, while guided paths find them more often. A path tracer without MIS
// (--strategy) and a film that clamps compare with the unguided samples' own variance. Where guiding is the less efficient by more than two standard errors, the rest of the
// budget renders without it; an uncertain trial keeps it. The tree is young: the trial cannot see
// what training still to come would gain (docs/comparison.md, "Switching itself off").
// "bool switchoff" false leaves guiding on. There is no trial under 14 samples per pixel, with
// --guiding-load, or where a time limit ends training sooner; the training cost to
// come is predicted by the sample budget, not the time limit.
// With --guiding-load there is no training: the image is one render with the tree read, so sample
// slices are exact and merge (scripts/render-distributed trains once); --guiding-save writes the
// trained tree.
#pragma once

#include "pbrt_ext/render.h"

namespace pbrt {

class Scene;

// Throws std::runtime_error for a tree file that cannot be read or written.
RenderStatistics RenderGuided(Scene &scene, SampleRange samples, const RenderOptions &options);

}  // namespace pbrt
