// The nanovdb target: the bytes as a .nvdb file that a scene's "nanovdb" medium reads, through
// LoadScene, so that NanoVDB's reader, its validator and the medium's own checks (values, bounds,
// majorants) see what a corrupt or hostile file holds. A rejection must carry the scene's
// location like any scene error.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/scene/sceneloader.h"
#include "pbrt_ext/util/log.h"

#include <string>
#include <string_view>

namespace pbrt::fuzz {

void FuzzNanoVDB(std::span<const uint8_t> data) {
    WriteScratchFile("nanovdb", "input.nvdb", data);
    constexpr std::string_view scene = R"(Film "rgb" "integer xresolution" 2 "integer yresolution" 2
WorldBegin
MakeNamedMedium "smoke" "string type" "nanovdb" "string filename" "input.nvdb"
MediumInterface "smoke" ""
Material "interface"
Shape "sphere"
)";
    std::string path = WriteScratchFile(
        "nanovdb", "scene.pbrt",
        std::span<const uint8_t>(reinterpret_cast<const uint8_t *>(scene.data()), scene.size()));
    Log().quiet = true;
    ExpectReadOrRejection("nanovdb", [&] { LoadScene(path, RenderOverrides()); });
}

}  // namespace pbrt::fuzz
