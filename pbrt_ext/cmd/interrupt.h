// Ctrl-C (SIGINT) for the pbrt_ext command: the first one during a render stops it and keeps what
// was rendered; any other ends the program at once. The library never installs a signal handler
// (a host program owns its signals); it only reads RenderOptions::cancel, which this sets.
//
// Every SIGINT that ends the program exits with kInterruptedExitStatus, after removing the
// temporary file of an image being written (util/atomicfile.h), so neither a partial image nor a
// stray temporary file is left. The handler runs on the thread the kernel picks: Linux picks the
// main thread, which is the one writing images, so the write cannot go on past the removal.
#pragma once

#include <atomic>
#include <cstdint>

namespace pbrt {

// 128 + SIGINT, the status shells report for a program that SIGINT ended.
constexpr int kInterruptedExitStatus = 130;

// From here on a SIGINT ends the program (the scene is loading: there is nothing to keep). Does
// nothing where SIGINT is ignored, as in a background job of a non-interactive shell.
void InstallInterruptHandler();

// Between the two, the first SIGINT sets RenderInterrupt() and says on stderr that the render
// stops at the next tile boundary. Another within kSameInterruptNanoseconds of it is the same
// interrupt delivered twice (to the process and to its group) and changes nothing; one later is
// a deliberate second Ctrl-C and ends the program without writing the image.
constexpr int64_t kSameInterruptNanoseconds = 1000000000;
void BeginInterruptibleRender();
void EndInterruptibleRender();

// For RenderOptions::cancel.
const std::atomic<bool> &RenderInterrupt();

}  // namespace pbrt
