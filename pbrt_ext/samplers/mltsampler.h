// pbrt-v4's MLTSampler: the primary sample space of Kelemen et al.'s Metropolis light transport
// ("A Simple and Robust Mutation Strategy for the Metropolis Light Transport Algorithm", 2002).
// A state is a vector of values in [0, 1) that a path is made from; a proposal either replaces
// them all (a large step, with probability largeStepProbability) or moves each by a normal
// perturbation of standard deviation sigma, wrapped around [0, 1). Values are made when a path
// first asks for them and mutated lazily: one a path has not read since the last large step is
// drawn afresh, and the small steps it missed are applied at once (their sum is a normal of
// sigma sqrt(n)). Values are interleaved in streams (camera, light, connection), so that a
// change in one subpath's length does not shift the values the others read.
#pragma once

#include "pbrt_ext/pbrt.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/vecmath.h"

#include <cstdint>
#include <string>
#include <vector>

namespace pbrt {

class MLTSampler {
  public:
    // rngSequenceIndex and seed select the random sequence (a bootstrap sample's index: a
    // chain that starts from it replays that sample first).
    MLTSampler(int mutationsPerPixel, int64_t rngSequenceIndex, Float sigma,
               Float largeStepProbability, int streamCount, int seed);

    static constexpr const char *Name() { return "mlt"; }
    int SamplesPerPixel() const { return mutationsPerPixel; }

    // The next proposal: a large step or small ones.
    void StartIteration();
    // Keeps the proposal as the chain's state.
    void Accept();
    // Restores the state the proposal was made from.
    void Reject();
    // Reads from stream index, from its first value.
    void StartStream(int index);

    // pbrt-v4's Sampler interface, for the code that makes paths from the values. A primary
    // sample space has no pixels: StartPixelSample only reseeds the random sequence.
    void StartPixelSample(Point2i p, int sampleIndex, int dimension = 0);
    Float Get1D();
    Point2f Get2D() { return {Get1D(), Get1D()}; }
    Point2f GetPixel2D() { return Get2D(); }

    std::string ToString() const;

  private:
    struct PrimarySample {
        Float value = 0;
        // The iteration that last changed it, and what it was before the current proposal.
        int64_t lastModificationIteration = 0;
        Float valueBackup = 0;
        int64_t modifyBackup = 0;

        void Backup() {
            valueBackup = value;
            modifyBackup = lastModificationIteration;
        }
        void Restore() {
            value = valueBackup;
            lastModificationIteration = modifyBackup;
        }
    };

    // Brings value index up to the current iteration.
    void EnsureReady(int index);
    int NextIndex() { return streamIndex + streamCount * sampleIndex++; }

    int mutationsPerPixel;
    RNG rng;
    Float sigma, largeStepProbability;
    int streamCount;
    std::vector<PrimarySample> X;
    int64_t currentIteration = 0;
    bool largeStep = true;
    int64_t lastLargeStepIteration = 0;
    int streamIndex = 0, sampleIndex = 0;
};

}  // namespace pbrt
