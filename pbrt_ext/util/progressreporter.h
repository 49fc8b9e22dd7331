// A progress bar with elapsed time and ETA on stderr, redrawn by its own thread (pbrt-v4's
// src/pbrt/util/progressreporter.h). Update() is lock-free and cheap enough to call per tile.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace pbrt {

class ProgressReporter {
  public:
    ProgressReporter(int64_t totalWork, std::string title, bool quiet);
    ~ProgressReporter();
    ProgressReporter(const ProgressReporter &) = delete;
    ProgressReporter &operator=(const ProgressReporter &) = delete;

    void Update(int64_t work = 1) { workDone += work; }
    // Draws the final state and stops the drawing thread.
    void Done();
    double ElapsedSeconds() const;

  private:
    void Draw(bool final) const;

    const int64_t totalWork;
    const std::string title;
    const std::chrono::steady_clock::time_point start = std::chrono::steady_clock::now();
    std::atomic<int64_t> workDone{0};
    std::mutex mutex;
    std::condition_variable wake;
    bool exit = false;
    std::thread drawer;
};

}  // namespace pbrt
