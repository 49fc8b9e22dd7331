// Guided rendering's training schedule (integrators/trainingschedule.h): iterations of doubling
// sample counts take just under half of the budget; the trial, in place of the third iteration
// after 3 samples per pixel, fits from 14 samples per pixel; a guided ray costs training's weight
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
    // From the trial on (7 samples done, iteration 3 next).
    EXPECT_EQ(TrainingToCome(7, 64, 3), 8 + 16);
    EXPECT_EQ(TrainingToCome(7, 29, 3), 0);
}

TEST(TrainingSchedule, TheTrialNeedsFourteenSamplesPerPixel) {
    // The trial takes the place of iteration 2 (4 samples per pixel, after 1 + 2).
    EXPECT_EQ(IterationSamples(2), 4);
    EXPECT_TRUE(IterationFits(3, 14, 2));
    EXPECT_FALSE(IterationFits(3, 13, 2));
}

TEST(TrainingSchedule, AGuidedRayCostsTrainingsWeightWhileTrainingIsToCome) {
    // 64 spp after the trial: 8 + 16 more of training, then 33 of rendering.
    EXPECT_DOUBLE_EQ(GuidedRayCost(7, 64, 3), (24 * kTrainingRayCost + 33 * kGuidedRayCost) / 57);
    // No training left: rendering's cost; nothing left at all: the same.
    EXPECT_DOUBLE_EQ(GuidedRayCost(7, 29, 3), kGuidedRayCost);
    EXPECT_DOUBLE_EQ(GuidedRayCost(64, 64, 3), kGuidedRayCost);
    // The larger the share of training to come, the dearer a guided ray: at 256 spp it is 120 of
    // the 249 samples per pixel left.
    EXPECT_DOUBLE_EQ(GuidedRayCost(7, 256, 3), (120 * kTrainingRayCost + 129 * kGuidedRayCost) / 249);
    EXPECT_GT(GuidedRayCost(7, 256, 3), GuidedRayCost(7, 64, 3));
}

}  // namespace
