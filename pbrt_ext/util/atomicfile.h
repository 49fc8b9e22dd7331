// Files that appear complete or not at all: written under a temporary name beside the target and
// renamed into place (rename(2) replaces the target atomically within a directory), so that a
// failed write, a crash or an interrupt never leaves a partial file under the target's name.
//
// A process killed by a signal runs no destructors, so the temporary names being written are also
// recorded where a signal handler can read them: a program whose handler ends the process calls
// RemoveUnfinishedFiles() first and leaves nothing behind (cmd/interrupt.h does).
#pragma once

#include <functional>
#include <string>

namespace pbrt {

// Runs write(tmpPath), then renames tmpPath onto path. On any exception, from write or from the
// rename, the temporary file is removed, the target is left as it was, and the exception
// propagates; a failed rename throws std::runtime_error("<path>: error: <why>"). Concurrent calls
// are safe: each gets its own temporary name (".<name>.tmp-<pid>-<n>" beside path).
void WriteFileAtomically(const std::string &path,
                         const std::function<void(const std::string &tmpPath)> &write);

// Removes the temporary files of the writes in progress, with unlink(2) alone: async-signal-safe,
// for a signal handler that then ends the process (the writes themselves go on until it does).
// Writes beyond the 16 in progress at once, or with a path longer than PATH_MAX, are not
// recorded; the handler then may leave their hidden temporary file, never a partial target.
void RemoveUnfinishedFiles();

}  // namespace pbrt
