#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <unistd.h>

#include <atomic>
#include <filesystem>
#include <limits>
#include <system_error>

namespace pbrt {

namespace {

constexpr uint64_t kSaturated = std::numeric_limits<uint64_t>::max();

// 0: the physical memory.
std::atomic<uint64_t> chosenBudget{0};

uint64_t PhysicalMemory() {
    long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGE_SIZE);
    // Unknown (never on Linux): only what 64 bits cannot count is refused.
    if (pages <= 0 || pageSize <= 0) return kSaturated;
    return SaturatingProduct({uint64_t(pages), uint64_t(pageSize)});
}

// "1.5 GiB": the largest binary unit that keeps the number at 1 or more.
std::string HumanBytes(uint64_t bytes) {
    constexpr const char *kUnits[] = {"KiB", "MiB", "GiB", "TiB", "PiB", "EiB"};
    double value = double(bytes) / 1024;
    int unit = 0;
    for (; value >= 1024 && unit + 1 < int(std::size(kUnits)); ++unit) value /= 1024;
    return fmt::format("{:.1f} {}", value, kUnits[unit]);
}

}  // namespace

uint64_t MemoryBudget() {
    uint64_t chosen = chosenBudget.load();
    static const uint64_t physical = PhysicalMemory();
    return chosen ? chosen : physical;
}

void SetMemoryBudget(uint64_t bytes) { chosenBudget.store(bytes); }

uint64_t SaturatingProduct(std::initializer_list<uint64_t> factors) {
    uint64_t product = 1;
    for (uint64_t f : factors)
        if (__builtin_mul_overflow(product, f, &product)) return kSaturated;
    return product;
}

void CheckMemory(const FileLoc &loc, std::string_view what, uint64_t bytes) {
    uint64_t budget = MemoryBudget();
    if (bytes <= budget) return;
    std::string need = bytes == kSaturated ? "more than 2^64 bytes"
                                           : fmt::format("{} bytes ({})", bytes, HumanBytes(bytes));
    throw ParseError(loc, fmt::format("{} would take {} of memory; expected at most the memory "
                                      "budget of {} bytes ({}, {})",
                                      what, need, budget, HumanBytes(budget),
                                      chosenBudget.load() ? "set by the application"
                                                          : "this machine's physical memory"));
}

std::optional<uint64_t> RegularFileSize(const std::string &path, std::string *why) {
    std::error_code ec;
    uintmax_t size = std::filesystem::file_size(path, ec);
    if (!ec) return size;
    // file_size fails for anything but a regular file; the system's message names the common
    // cases (missing, a directory) but not a device.
    std::error_code ignored;
    if (why)
        *why = std::filesystem::is_other(path, ignored)
                   ? "not a regular file (a device or pipe may never end); expected a file"
                   : ec.message();
    return std::nullopt;
}

}  // namespace pbrt
