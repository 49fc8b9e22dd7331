#include "pbrt_ext/util/atomicfile.h"

#include <fmt/format.h>

#include <fcntl.h>
#include <limits.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <system_error>

namespace pbrt {

namespace {

// One temporary file being written, in static storage a signal handler may read: no allocation,
// and a lock-free flag says when the path is complete.
struct UnfinishedFile {
    std::atomic<bool> claimed{false};  // by a writer
    std::atomic<bool> named{false};    // path holds the complete temporary name
    char path[PATH_MAX];
};
static_assert(std::atomic<bool>::is_always_lock_free, "a signal handler reads the flags");

constexpr int kMaxUnfinishedFiles = 16;
UnfinishedFile unfinishedFiles[kMaxUnfinishedFiles];

// Records a temporary name from before the file is created until after it is renamed or removed.
class UnfinishedFileRecord {
  public:
    explicit UnfinishedFileRecord(const std::string &path) {
        if (path.size() >= sizeof(UnfinishedFile::path))
            return;
        for (UnfinishedFile &file : unfinishedFiles)
            if (!file.claimed.exchange(true)) {
                std::memcpy(file.path, path.c_str(), path.size() + 1);
                file.named.store(true);
                entry = &file;
                return;
            }
    }
    ~UnfinishedFileRecord() {
        if (!entry)
            return;
        entry->named.store(false);
        entry->claimed.store(false);
    }
    UnfinishedFileRecord(const UnfinishedFileRecord &) = delete;
    UnfinishedFileRecord &operator=(const UnfinishedFileRecord &) = delete;

  private:
    UnfinishedFile *entry = nullptr;
};

// Unique per process and call, so that concurrent writers never share a temporary file.
std::string TemporaryPathFor(const std::string &path) {
    static std::atomic<unsigned> counter{0};
    std::filesystem::path p(path);
    std::string name = fmt::format(".{}.tmp-{}-{}", p.filename().string(), ::getpid(), counter++);
    return (p.parent_path() / name).string();
}

// Without it, a power loss soon after the rename can leave the target renamed but empty: file
// systems may commit the rename before the data (ext4 with delalloc, for one).
void FlushToDisk(const std::string &tmpPath, const std::string &path) {
    int fd = ::open(tmpPath.c_str(), O_RDONLY);
    if (fd < 0 || ::fsync(fd) != 0) {
        int error = errno;
        if (fd >= 0) ::close(fd);
        throw std::runtime_error(path + ": error: cannot flush the written file to disk: " +
                                 std::strerror(error));
    }
    ::close(fd);
}

}  // namespace

void WriteFileAtomically(const std::string &path,
                         const std::function<void(const std::string &tmpPath)> &write) {
    const std::string tmpPath = TemporaryPathFor(path);
    UnfinishedFileRecord record(tmpPath);
    try {
        write(tmpPath);
        FlushToDisk(tmpPath, path);
        std::error_code ec;
        std::filesystem::rename(tmpPath, path, ec);
        if (ec)
            throw std::runtime_error(path + ": error: cannot rename the temporary file into " +
                                     "place: " + ec.message());
    } catch (...) {
        std::error_code ignored;
        std::filesystem::remove(tmpPath, ignored);
        throw;
    }
}

void RemoveUnfinishedFiles() {
    // A name whose file was not created yet, or was renamed already, fails with ENOENT: harmless.
    // (A path is read without a lock: another thread that ended one write and began the next at
    // this very moment could be rewriting it. The command line writes one image at a time.)
    for (UnfinishedFile &file : unfinishedFiles)
        if (file.named.load())
            ::unlink(file.path);
}

}  // namespace pbrt
