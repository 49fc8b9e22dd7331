#include "pbrt_ext/util/resourcelimits.h"

#include <fmt/format.h>

#include <unistd.h>

#include <atomic>
#include <cctype>
#include <charconv>
#include <filesystem>
#include <fstream>
#include <limits>
#include <system_error>

namespace pbrt {

namespace {

constexpr uint64_t kSaturated = std::numeric_limits<uint64_t>::max();

// 0: the default (the physical memory or the cgroup's limit).
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

// The budget when the application chose none, and where it comes from.
struct DefaultBudget {
    uint64_t bytes;
    const char *source;
};

DefaultBudget ComputeDefaultBudget() {
    uint64_t physical = PhysicalMemory();
    std::optional<uint64_t> cgroup = CgroupMemoryLimit();
    if (cgroup && *cgroup < physical) return {*cgroup, "the memory limit of this process's cgroup"};
    return {physical, "the physical memory"};
}

// Read once: neither changes while a scene loads.
const DefaultBudget &Default() {
    static const DefaultBudget budget = ComputeDefaultBudget();
    return budget;
}

std::optional<std::string> ReadSmallFile(const std::string &path) {
    std::ifstream in(path);
    std::string contents;
    if (!std::getline(in, contents)) return std::nullopt;
    return contents;
}

}  // namespace

std::optional<uint64_t> ParseCgroupMemoryLimit(std::string_view contents) {
    while (!contents.empty() && std::isspace((unsigned char)contents.back())) contents.remove_suffix(1);
    uint64_t bytes = 0;
    auto [end, error] = std::from_chars(contents.data(), contents.data() + contents.size(), bytes);
    if (error != std::errc() || end != contents.data() + contents.size() || contents.empty())
        return std::nullopt;
    return bytes;
}

std::optional<uint64_t> CgroupMemoryLimit() {
    // Lines "id:controllers:path": "0::path" is the v2 group, a list naming "memory" the v1 one.
    std::ifstream groups("/proc/self/cgroup");
    for (std::string line; std::getline(groups, line);) {
        size_t first = line.find(':'), second = line.find(':', first + 1);
        if (first == std::string::npos || second == std::string::npos) continue;
        std::string controllers = line.substr(first + 1, second - first - 1);
        std::string group = line.substr(second + 1);
        std::string file;
        if (line.starts_with("0::"))
            file = "/sys/fs/cgroup" + group + "/memory.max";
        else if (("," + controllers + ",").find(",memory,") != std::string::npos)
            file = "/sys/fs/cgroup/memory" + group + "/memory.limit_in_bytes";
        else
            continue;
        if (std::optional<std::string> contents = ReadSmallFile(file))
            if (std::optional<uint64_t> limit = ParseCgroupMemoryLimit(*contents)) return limit;
    }
    return std::nullopt;
}

uint64_t MemoryBudget() {
    uint64_t chosen = chosenBudget.load();
    return chosen ? chosen : Default().bytes;
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
                                                          : Default().source));
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
