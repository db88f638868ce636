#include "output_file.h"

#include <sys/stat.h>
#if defined(_WIN32)
#define WIN32_LEAN_AND_MEAN
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <io.h>
#include <process.h>
#include <windows.h>
#else
#include <unistd.h>
#endif

#include <cerrno>
#include <cstdio>
#include <cstring>

namespace bricklight::render {

const char* pathSeparators() {
#if defined(_WIN32)
    return "/\\";
#else
    return "/";
#endif
}

namespace {

std::string folderOf(const std::string& path) {
    const size_t slash = path.find_last_of(pathSeparators());
    if (slash == std::string::npos) return ".";
    // "/x" and, on Windows, "C:\\x": the root keeps its separator ("C:" alone is drive C's current folder).
    return slash == 0 || path[slash - 1] == ':' ? path.substr(0, slash + 1) : path.substr(0, slash);
}

std::string fileOf(const std::string& path) {
    const size_t slash = path.find_last_of(pathSeparators());
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

bool folderWritable(const std::string& folder) {
#if defined(_WIN32)
    return _access(folder.c_str(), 2) == 0;  // 2: write (there is no search permission to ask for)
#else
    return access(folder.c_str(), W_OK | X_OK) == 0;
#endif
}

}  // namespace

bool checkOutputPath(const std::string& path, std::string* error) {
    auto fail = [&](const std::string& why) {
        if (error) *error = "cannot write '" + path + "': " + why;
        return false;
    };
    if (path.empty() || fileOf(path).empty()) return fail("no file name");
    const std::string folder = folderOf(path);
    struct stat st{};
    if (stat(folder.c_str(), &st) != 0) return fail("folder '" + folder + "': " + std::strerror(errno));
    if (!S_ISDIR(st.st_mode)) return fail("'" + folder + "' is not a folder");
    if (!folderWritable(folder)) return fail("folder '" + folder + "' is not writable: " + std::strerror(errno));
    if (stat(path.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) return fail("it exists and is not a regular file");
    return true;
}

bool replaceFile(const std::string& from, const std::string& to, std::string* why) {
#if defined(_WIN32)
    if (MoveFileExA(from.c_str(), to.c_str(), MOVEFILE_REPLACE_EXISTING | MOVEFILE_WRITE_THROUGH)) return true;
    *why = "MoveFileEx failed (error " + std::to_string(GetLastError()) + ")";
    return false;
#else
    if (std::rename(from.c_str(), to.c_str()) == 0) return true;
    *why = std::string("rename failed: ") + std::strerror(errno);
    return false;
#endif
}

bool writeFileAtomically(const std::string& path, const std::function<bool(const std::string&, std::string*)>& write,
                         const std::function<bool(const std::string&, std::string*)>& check, std::string* error) {
    if (!checkOutputPath(path, error)) return false;
    const std::string name = fileOf(path);
    const size_t dot = name.find_last_of('.');
    const std::string extension = dot == std::string::npos ? "" : name.substr(dot);
    // Hidden, unique to this process, in the same folder (a rename is atomic only within one file system).
    const std::string temp = folderOf(path) + "/." + name + ".tmp" + std::to_string(getpid()) + extension;
    std::string why;
    errno = 0;
    bool ok = write(temp, &why);
    const int writeErrno = errno;  // encoders do not always say why (a full disk, a file-size limit)
    struct stat st{};
    if (ok && (stat(temp.c_str(), &st) != 0 || st.st_size == 0)) {
        ok = false;
        why = "the written file is empty";
    }
    if (ok && check) ok = check(temp, &why);
    if (ok) ok = replaceFile(temp, path, &why);
    if (!ok) {
        std::remove(temp.c_str());
        if (why.empty()) why = std::string("the write failed") + (writeErrno ? std::string(": ") + std::strerror(writeErrno) : "");
        if (error) *error = "cannot write '" + path + "': " + why;
    }
    return ok;
}

}  // namespace bricklight::render
