// Guided rendering's training schedule (integrators/trainingschedule.h): iterations of doubling
// sample counts take just under half of the budget; the trial, in place of the fourth iteration
// after 7 samples per pixel, fits from 30 samples per pixel; a guided ray costs training's weight
// while training is still to come, rendering's after.
#include "pbrt_ext/integrators/trainingschedule.h"

#include <gtest/gtest.h>

using namespace pbrt;

namespace {

TEST(TrainingSchedule, IterationsTakeUnderHalfTheBudget) {
    EXPECT_EQ(TrainingToCome(0, 64, 0), 1 + 2 + 4 + 8 + 16);
    EXPECT_EQ(TrainingToCome(0, 256, 0), 127);
    EXPECT_EQ(TrainingToCome(0, 30, 0), 15);  // 15 of 30: exactly half still fits
    EXPECT_EQ(TrainingToCome(0, 1, 0), 0);
    // From the trial on (15 samples done, iteration 4 next).
    EXPECT_EQ(TrainingToCome(15, 64, 4), 16);
    EXPECT_EQ(TrainingToCome(15, 32, 4), 0);
}

TEST(TrainingSchedule, TheTrialNeedsThirtySamplesPerPixel) {
    // The trial takes the place of iteration 3 (8 samples per pixel, after 1 + 2 + 4).
    EXPECT_EQ(IterationSamples(3), 8);
    EXPECT_TRUE(IterationFits(7, 30, 3));
    EXPECT_FALSE(IterationFits(7, 29, 3));
}

TEST(TrainingSchedule, AGuidedRayCostsTrainingsWeightWhileTrainingIsToCome) {
    // 64 spp after the trial: 16 more of training, then 33 of rendering.
    EXPECT_DOUBLE_EQ(GuidedRayCost(15, 64, 4), (16 * kTrainingRayCost + 33 * kGuidedRayCost) / 49);
    // No training left: rendering's cost; nothing left at all: the same.
    EXPECT_DOUBLE_EQ(GuidedRayCost(15, 32, 4), kGuidedRayCost);
    EXPECT_DOUBLE_EQ(GuidedRayCost(64, 64, 4), kGuidedRayCost);
    // The larger the share of training to come, the dearer a guided ray: at 256 spp it is 112 of
    // the 241 samples per pixel left.
    EXPECT_DOUBLE_EQ(GuidedRayCost(15, 256, 4), (112 * kTrainingRayCost + 129 * kGuidedRayCost) / 241);
    EXPECT_GT(GuidedRayCost(15, 256, 4), GuidedRayCost(15, 64, 4));
}

}  // namespace
