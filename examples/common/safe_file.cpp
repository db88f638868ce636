#include "safe_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "load_limits.h"

namespace bricklight::scenes {

namespace {

std::string kindOf(mode_t mode) {
    if (S_ISDIR(mode)) return "a directory";
    if (S_ISFIFO(mode)) return "a FIFO";
    if (S_ISCHR(mode) || S_ISBLK(mode)) return "a device";
    if (S_ISSOCK(mode)) return "a socket";
    return "not a regular file";
}

std::string realPath(const std::string& path) {
    char buffer[PATH_MAX];
    return ::realpath(path.c_str(), buffer) ? std::string(buffer) : std::string();
}

// "a/./b/../c" -> "a/c", from the root or the working folder: for paths that do not exist.
std::string lexicallyNormal(const std::string& path) {
    std::string absolute = path;
    if (path.empty() || path[0] != '/') {
        char cwd[PATH_MAX];
        absolute = std::string(::getcwd(cwd, sizeof cwd) ? cwd : "") + "/" + path;
    }
    std::vector<std::string> parts;
    size_t start = 0;
    while (start <= absolute.size()) {
        size_t end = absolute.find('/', start);
        if (end == std::string::npos) end = absolute.size();
        const std::string part = absolute.substr(start, end - start);
        if (part == "..") {
            if (!parts.empty()) parts.pop_back();
        } else if (!part.empty() && part != ".") {
            parts.push_back(part);
        }
        start = end + 1;
    }
    std::string out;
    for (const std::string& p : parts) out += "/" + p;
    return out.empty() ? "/" : out;
}

}  // namespace

RegularFile& RegularFile::operator=(RegularFile&& o) noexcept {
    if (this != &o) {
        if (fd_ >= 0) ::close(fd_);
        fd_ = o.fd_;
        size_ = o.size_;
        o.fd_ = -1;
    }
    return *this;
}

RegularFile::~RegularFile() {
    if (fd_ >= 0) ::close(fd_);
}

bool RegularFile::open(const std::string& path, uint64_t maxBytes, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = why;
        return false;
    };
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) return fail("'" + path + "': " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) return fail("'" + path + "' is " + kindOf(st.st_mode) + ", not a regular file: refused");
    // O_NONBLOCK: should the path have been swapped for a FIFO since stat(), opening it does not wait.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NOCTTY | O_NONBLOCK);
    if (fd < 0) return fail("'" + path + "': " + std::strerror(errno));
    if (::fstat(fd, &st) != 0 || !S_ISREG(st.st_mode)) {
        ::close(fd);
        return fail("'" + path + "' is " + kindOf(st.st_mode) + ", not a regular file: refused");
    }
    if (uint64_t(st.st_size) > maxBytes) {
        ::close(fd);
        return fail("'" + path + "' is " + std::to_string(st.st_size) + " bytes, over the limit of " + std::to_string(maxBytes) + " " +
                    raiseHint("maxFileBytes"));
    }
    if (fd_ >= 0) ::close(fd_);
    fd_ = fd;
    size_ = uint64_t(st.st_size);
    return true;
}

size_t RegularFile::readAt(uint64_t offset, void* out, size_t count) const {
    size_t done = 0;
    while (done < count) {
        const ssize_t n = ::pread(fd_, static_cast<char*>(out) + done, count - done, off_t(offset + done));
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) break;
        done += size_t(n);
    }
    return done;
}

bool readRegularFile(const std::string& path, uint64_t maxBytes, std::string* bytes, std::string* error) {
    RegularFile file;
    if (!file.open(path, maxBytes, error)) return false;
    bytes->resize(size_t(file.size()));
    if (file.readAt(0, bytes->data(), bytes->size()) != bytes->size()) {
        if (error) *error = "'" + path + "' could not be read completely";
        return false;
    }
    return true;
}

std::string canonicalFolderOf(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const std::string folder = slash == std::string::npos ? "." : slash == 0 ? "/" : path.substr(0, slash);
    return realPath(folder);
}

bool isInsideFolder(const std::string& path, const std::string& canonicalFolder) {
    if (canonicalFolder.empty()) return false;
    std::string resolved = realPath(path);
    if (resolved.empty()) {
        // A file that does not exist (yet): its folder resolved, its name as written.
        const size_t slash = path.find_last_of('/');
        const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
        const std::string folder = canonicalFolderOf(path);
        resolved = !folder.empty() && name != ".." && name != "." ? folder + "/" + name : lexicallyNormal(path);
    }
    if (canonicalFolder == "/") return true;
    return resolved == canonicalFolder || resolved.compare(0, canonicalFolder.size() + 1, canonicalFolder + "/") == 0;
}

std::string outsideFolderMessage(const std::string& path, const std::string& modelPath, const std::string& canonicalFolder) {
    return "'" + path + "' (named by '" + modelPath + "') lies outside the model's folder '" + canonicalFolder + "': refused " +
           raiseHint("allowOutsidePaths");
}

}  // namespace bricklight::scenes
