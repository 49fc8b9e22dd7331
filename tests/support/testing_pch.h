// The headers nearly every test includes, compiled once for all of them (tests/CMakeLists.txt):
// GoogleTest and the scene's headers take seconds to parse, more than most tests' own code.
// Each test still includes what it uses; this file only makes that cheap.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "pbrt_ext/images/image.h"
#include "pbrt_ext/render.h"
#include "pbrt_ext/scene.h"
#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/spectra/colorspace.h"
#include "pbrt_ext/util/rng.h"
#include "pbrt_ext/util/sampling.h"
