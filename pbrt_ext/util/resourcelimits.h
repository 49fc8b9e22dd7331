// Resource guards (host only). A scene file may ask for anything, so every allocation whose size
// a file decides (the film, an image, a mesh, a file read whole) is compared with a memory budget
// before it is made: a request that cannot fit becomes a located error, not an out-of-memory
// kill. Linux overcommits memory, so such a request would not fail when made but be killed later,
// while its pages are touched.
//
// The budget is the machine's physical memory, or the memory limit of the process's cgroup (a
// container's) where that is lower: one request larger than that cannot succeed.
// Requests are checked one at a time, so several that each fit may still exhaust memory
// together; the guard stops absurd requests, it does not account for the whole render.
#pragma once

#include "pbrt_ext/util/error.h"

#include <cstdint>
#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>

namespace pbrt {

// A text file of numbers, parsed: each number takes as few as two characters ("0 ") and becomes
// an 8-byte double while parsed, then a 4-byte float in the scene, besides the text itself held
// during parsing: up to 1 + 4 + 2 bytes of memory per byte of the file, rounded up.
constexpr uint64_t kParsedTextBytesPerByte = 8;

// The bytes one request may take: the physical memory or the cgroup's limit, whichever is lower,
// unless SetMemoryBudget chose a budget.
uint64_t MemoryBudget();
// For tests, and for applications that embed the renderer with less memory to give it;
// 0 restores the default.
void SetMemoryBudget(uint64_t bytes);

// The memory limit of this process's cgroup (cgroup v2's memory.max, or v1's
// memory.limit_in_bytes, of the group /proc/self/cgroup names); std::nullopt where none is set
// or none can be read.
std::optional<uint64_t> CgroupMemoryLimit();
// The contents of such a file: a byte count, or std::nullopt for "max" (no limit) or anything
// that is not a number.
std::optional<uint64_t> ParseCgroupMemoryLimit(std::string_view contents);

// The product, or UINT64_MAX (more than any budget) where it would overflow.
uint64_t SaturatingProduct(std::initializer_list<uint64_t> factors);

// Throws ParseError at loc when bytes exceed the budget: "<what> would take N bytes (x GiB) of
// memory; expected at most the memory budget of M bytes (y GiB, <where the budget comes from>)".
void CheckMemory(const FileLoc &loc, std::string_view what, uint64_t bytes);

// The size of the file at path, to be read whole; std::nullopt when it cannot be, with *why (if
// why is not null) the system's reason (no such file, a directory) or, for a device, pipe or
// socket, which may never end (/dev/zero) or never start (a FIFO), that it is not a regular file.
std::optional<uint64_t> RegularFileSize(const std::string &path, std::string *why);

}  // namespace pbrt
