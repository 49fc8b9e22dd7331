#include "pbrt_ext/util/progressreporter.h"

#include <algorithm>
#include <cstdio>

namespace pbrt {

ProgressReporter::ProgressReporter(int64_t totalWork, std::string title, bool quiet)
    : totalWork(std::max<int64_t>(1, totalWork)), title(std::move(title)) {
    if (quiet)
        return;
    drawer = std::thread([this] {
        std::unique_lock<std::mutex> lock(mutex);
        while (!wake.wait_for(lock, std::chrono::milliseconds(250), [this] { return exit; }))
            Draw(false);
    });
}

ProgressReporter::~ProgressReporter() { Done(); }

void ProgressReporter::Done() {
    {
        std::lock_guard<std::mutex> lock(mutex);
        if (exit)
            return;
        exit = true;
    }
    wake.notify_all();
    if (drawer.joinable()) {
        drawer.join();
        Draw(true);
    }
}

double ProgressReporter::ElapsedSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void ProgressReporter::Draw(bool final) const {
    constexpr int kBarWidth = 40;
    double fraction = std::min(1.0, double(workDone) / double(totalWork));
    int filled = int(fraction * kBarWidth);
    std::string bar(filled, '=');
    if (filled < kBarWidth)
        bar += '>' + std::string(kBarWidth - filled - 1, ' ');
    double elapsed = ElapsedSeconds();
    char eta[32] = "?";
    if (fraction > 0)
        std::snprintf(eta, sizeof(eta), "%.1fs", elapsed / fraction - elapsed);
    std::fprintf(stderr, "\r%s [%s] %3d%% (%.1fs elapsed, ETA %s)%s", title.c_str(), bar.c_str(),
                 int(100 * fraction), elapsed, final ? "0.0s" : eta, final ? "\n" : "");
    std::fflush(stderr);
}

}  // namespace pbrt
