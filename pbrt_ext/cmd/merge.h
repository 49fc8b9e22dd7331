// pbrt_ext merge OUT.exr SLICE.exr...: adds film slices (renders of disjoint sample ranges,
// pbrt_ext --samples A:B) up to the image one render of all their samples gives, itself a slice
// that merges further (filmslice.h). Slices of different renders, overlapping slices and slices
// that leave samples out between them are refused with the reason, exit status 1 and no output.
#pragma once

namespace pbrt {

// argv[0] is "merge".
int MergeMain(int argc, char **argv);

}  // namespace pbrt
