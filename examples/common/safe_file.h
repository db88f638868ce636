// Files named by a model (and the model itself), opened so that they cannot cost more than a limit:
// regular files only (never /dev/zero, a FIFO, a directory or a device, which readers probe forever or
// block on), of bounded size, and where asked, only inside a folder.
#pragma once

#include <cstdint>
#include <string>

namespace bricklight::scenes {

// An open regular file (closed on destruction).
class RegularFile {
public:
    RegularFile() = default;
    RegularFile(RegularFile&& o) noexcept : fd_(o.fd_), size_(o.size_) { o.fd_ = -1; }
    RegularFile& operator=(RegularFile&& o) noexcept;
    RegularFile(const RegularFile&) = delete;
    RegularFile& operator=(const RegularFile&) = delete;
    ~RegularFile();

    // Opens `path` for reading. Refuses what is not a regular file (checked before opening, so that
    // opening a device has no effect, and again on the open file) and files over `maxBytes` bytes.
    // `error`: "'path' is not a regular file..." / "'path' is N bytes, over the limit of M (raise it...)".
    bool open(const std::string& path, uint64_t maxBytes, std::string* error);
    bool isOpen() const { return fd_ >= 0; }
    uint64_t size() const { return size_; }
    // Reads up to `count` bytes at `offset`; returns how many were read (short only at the end or on error).
    size_t readAt(uint64_t offset, void* out, size_t count) const;

private:
    int fd_ = -1;
    uint64_t size_ = 0;
};

// The whole of a regular file of at most `maxBytes` bytes (RegularFile::open's refusals).
bool readRegularFile(const std::string& path, uint64_t maxBytes, std::string* bytes, std::string* error);

// The folder that holds `path`, resolved through symbolic links ("" if it does not exist).
std::string canonicalFolderOf(const std::string& path);
// Whether `path` lies inside `canonicalFolder` once symbolic links are resolved (a link inside that points
// outside is outside). A path that does not exist is resolved through its folder, or else lexically.
bool isInsideFolder(const std::string& path, const std::string& canonicalFolder);
// "'<path>' lies outside the model's folder '<folder>'; ... (allow it with --allow-outside-paths ...)".
std::string outsideFolderMessage(const std::string& path, const std::string& modelPath, const std::string& canonicalFolder);

}  // namespace bricklight::scenes
