#include "pbrt_ext/cmd/interrupt.h"

#include "pbrt_ext/util/atomicfile.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <ctime>
#include <string_view>

namespace pbrt {

namespace {

// Lock-free atomics are the only shared state a signal handler may touch (C++17 [support.signal]).
static_assert(std::atomic<bool>::is_always_lock_free);
std::atomic<bool> renderRunning{false};
std::atomic<bool> interruptRequested{false};
static_assert(std::atomic<int64_t>::is_always_lock_free);
std::atomic<int64_t> firstInterruptNanoseconds{0};

// CLOCK_MONOTONIC, which clock_gettime reads async-signal-safely (POSIX).
int64_t NowNanoseconds() {
    timespec t{};
    ::clock_gettime(CLOCK_MONOTONIC, &t);
    return int64_t(t.tv_sec) * 1000000000 + t.tv_nsec;
}

// write(2): stdio is not async-signal-safe. A failed write leaves nothing to do.
void Say(std::string_view message) {
    [[maybe_unused]] ssize_t written = ::write(STDERR_FILENO, message.data(), message.size());
}

void OnInterrupt(int) {
    const int savedErrno = errno;  // the interrupted code may be about to read it
    if (renderRunning.load()) {
        const int64_t now = NowNanoseconds();
        if (!interruptRequested.exchange(true)) {
            firstInterruptNanoseconds.store(now);
            Say("\npbrt_ext: interrupt: stopping at the next tile boundary to write the image "
                "(interrupt again, a second later, to quit without writing)\n");
            errno = savedErrno;
            return;
        }
        // The same interrupt, delivered twice: a shell or `timeout` signals the process and its
        // group together, and a person does not press Ctrl-C twice within this interval.
        if (now - firstInterruptNanoseconds.load() < kSameInterruptNanoseconds) {
            errno = savedErrno;
            return;
        }
    }
    Say("\npbrt_ext: interrupted: quitting without writing the image\n");
    RemoveUnfinishedFiles();
    ::_exit(kInterruptedExitStatus);
}

}  // namespace

void InstallInterruptHandler() {
    // A program started with SIGINT ignored (a background job of a non-interactive shell) keeps
    // ignoring it: the terminal's Ctrl-C is not meant for it.
    struct sigaction previous = {};
    if (sigaction(SIGINT, nullptr, &previous) == 0 && previous.sa_handler == SIG_IGN)
        return;
    struct sigaction action = {};
    action.sa_handler = OnInterrupt;
    sigemptyset(&action.sa_mask);
    // The first SIGINT lets the program go on: system calls it interrupted resume, not fail.
    action.sa_flags = SA_RESTART;
    sigaction(SIGINT, &action, nullptr);
}

void BeginInterruptibleRender() { renderRunning.store(true); }

void EndInterruptibleRender() { renderRunning.store(false); }

const std::atomic<bool> &RenderInterrupt() { return interruptRequested; }

}  // namespace pbrt
