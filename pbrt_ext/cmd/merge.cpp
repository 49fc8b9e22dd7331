#include "pbrt_ext/cmd/merge.h"

#include "pbrt_ext/film/filmslice.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <string>
#include <utility>
#include <vector>

namespace pbrt {

int MergeMain(int argc, char **argv) {
    CLI::App app("pbrt_ext merge: adds film slices (pbrt_ext --samples A:B) up to the image of "
                 "all their samples",
                 "pbrt_ext merge");
    std::string out;
    std::vector<std::string> inputs;
    bool quiet = false;
    app.add_option("out", out, "the merged slice (EXR)")->required();
    app.add_option("slices", inputs, "slices of one render with adjoining sample ranges")
        ->required()
        ->check(CLI::ExistingFile);
    app.add_flag("--quiet", quiet, "print nothing but errors (default: off)");
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        // Help is success; anything else a bad command line (cmd/commandline.h).
        return app.exit(e) == 0 ? 0 : 2;
    }
    try {
        // One slice in memory at a time besides the sum, however many there are.
        FilmSliceMerger merger;
        for (const std::string &path : inputs) merger.Add(FilmSlice::Read(path), path);
        FilmSlice merged = std::move(merger).Result();
        merged.Write(out);
        if (!quiet)
            std::fprintf(stderr, "pbrt_ext merge: samples %d:%d of %zu slices written to %s\n",
                         merged.samples.first, merged.samples.last, inputs.size(), out.c_str());
    } catch (const std::exception &e) {
        std::fprintf(stderr, "%s\n", e.what());
        return 1;
    }
    return 0;
}

}  // namespace pbrt
