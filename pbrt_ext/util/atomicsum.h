// A sum that threads add to without a lock, and that copies (as a value) with what it holds.
#pragma once

#include <atomic>

namespace pbrt {

struct AtomicSum {
    AtomicSum() = default;
    AtomicSum(const AtomicSum &other) : value(other.Load()) {}
    AtomicSum &operator=(const AtomicSum &other) {
        value.store(other.Load(), std::memory_order_relaxed);
        return *this;
    }
    void Add(double v) { value.fetch_add(v, std::memory_order_relaxed); }
    double Load() const { return value.load(std::memory_order_relaxed); }
    void Store(double v) { value.store(v, std::memory_order_relaxed); }
    std::atomic<double> value{0};
};

}  // namespace pbrt
