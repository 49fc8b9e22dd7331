// The parser target: scene text through the tokenizer, the parser and BasicSceneBuilder.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/scene/scenedescription.h"
#include "pbrt_ext/util/log.h"

#include <string>

namespace pbrt::fuzz {

void FuzzParser(std::span<const uint8_t> data) {
    // Named as a file in an empty scratch folder: relative Includes resolve against the text's
    // folder, and there they find nothing.
    static const std::string name = (ScratchDirectory("parser") / "input.pbrt").string();
    Log().quiet = true;  // unsupported features warn; millions of warnings would only slow us down
    std::string text(reinterpret_cast<const char *>(data.data()), data.size());
    ExpectReadOrRejection("parser", [&] { DescribeSceneString(std::move(text), name); });
}

}  // namespace pbrt::fuzz
