// The scene target: a whole scene file through LoadScene, so that every create_* function, the
// resource guards and the scene build (Embree included, uninstrumented) see what the parser lets
// through. The file lies alone in a scratch folder: the meshes, images and spectra it names by
// relative path do not exist, which makes those references errors rather than slow reads.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/log.h"

#include <string>

namespace pbrt::fuzz {

void FuzzScene(std::span<const uint8_t> data) {
    std::string path = WriteScratchFile("scene", "input.pbrt", data);
    Log().quiet = true;
    ExpectReadOrRejection("scene", [&] { LoadScene(path, RenderOverrides()); });
}

}  // namespace pbrt::fuzz
