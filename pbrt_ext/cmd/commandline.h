// The pbrt_ext command's arguments, in pbrt-v4's syntax and with its meaning (pbrt-v4's
// src/pbrt/cmd/pbrt.cpp): "--name value", "--name=value" or "-name value"; names match ignoring
// case, '-' and '_'; lists are comma-separated ("--cropwindow 0,0.5,0,0.5"); flags take no value
// or "=true"/"=false"; a repeated option: the last one wins. Every word that is not an option is
// a scene file, read in order as one scene; "-" is standard input.
//
// pbrt-v4's options come first in --help, then ours; docs/cli.md has the table of both.
#pragma once

#include "pbrt_ext/options.h"

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace pbrt {

// The exit statuses of the pbrt_ext command (docs/cli.md).
constexpr int kExitSuccess = 0;
constexpr int kExitBadInput = 1;        // a bad scene, mesh, image or tree; a failed render
constexpr int kExitBadCommandLine = 2;  // an unknown option, a bad value
// kInterruptedExitStatus (130, cmd/interrupt.h): Ctrl-C.

// What --log-level lets through: pbrt-v4's levels.
enum class LogLevel { Verbose, Error, Fatal };

struct CommandLine {
    std::vector<std::string> sceneFiles;  // in order; "-" is standard input
    RenderOverrides overrides;
    std::string samples;                  // --samples A:B or k/K (empty: all)
    bool help = false, version = false;
    LogLevel logLevel = LogLevel::Error;
    std::string logFile;
    bool wavefront = false;               // pbrt-v4's wavefront integrator: volpath here
    // What to do between waves (cmd/waveobservers.h), with overrides' MSE reference.
    bool writePartialImages = false;
    std::string displayServer;            // host:port of tev
    // pbrt-v4's --format, --toply and --upgrade: print the scene (scene/formatter.h) instead of
    // rendering it.
    enum class Reformat { None, Format, ToPLY, Upgrade } reformat = Reformat::None;
    std::optional<Point2i> pixelMaterial;  // print what this pixel sees instead of rendering
};

// A command line that can't be followed; what() names the option and what it expects.
class CommandLineError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// The arguments after the program's name. Throws CommandLineError.
CommandLine ParseCommandLine(const std::vector<std::string> &args);

// The text --help prints.
std::string CommandLineHelp();

}  // namespace pbrt
