// The slice target: a film slice's EXR (filmslice.h) read by FilmSlice::Read, then merged with a
// copy of itself moved past its own samples, as `pbrt_ext merge` does (FilmSliceMerger). OpenEXR decodes the file;
// the target steers by what FilmSlice makes of its attributes and channels. The EXR signature is
// restored, so that every input reaches OpenEXR rather than being refused by its first bytes.
#include "fuzz/finding.h"
#include "fuzz/fuzz_targets.h"
#include "fuzz/scratch.h"

#include "pbrt_ext/film/filmslice.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <vector>

namespace pbrt::fuzz {

void FuzzSlice(std::span<const uint8_t> data) {
    constexpr uint8_t kExrSignature[] = {0x76, 0x2f, 0x31, 0x01};
    if (data.size() < std::size(kExrSignature))
        return;
    std::vector<uint8_t> file(data.begin(), data.end());
    std::copy(std::begin(kExrSignature), std::end(kExrSignature), file.begin());
    std::string path = WriteScratchFile("slice", "input.exr", file);
    ExpectReadOrRejection("slice", [&] {
        FilmSlice next = FilmSlice::Read(path);
        const SampleRange first = next.samples;
        const size_t sums = next.sums.size();
        FilmSliceMerger merger;  // two slices in memory, as the reader's budget counts
        merger.Add(next, path);
        next.samples = {first.last, first.last + first.Count()};
        merger.Add(std::move(next), path);
        FilmSlice merged = std::move(merger).Result();
        if (merged.samples != SampleRange{first.first, first.last + first.Count()} || merged.sums.size() != sums)
            ReportFinding("slice", "the merge of two adjoining slices is not their union");
        merged.GetImage();
    });
}

}  // namespace pbrt::fuzz
