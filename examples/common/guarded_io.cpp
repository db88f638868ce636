#include "guarded_io.h"

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <limits>
#include <memory>

#include "model_checks.h"
#include "safe_file.h"

namespace bricklight::scenes {

namespace {

// One open file; the aiFile that assimp holds points back to it through its UserData.
struct OpenFile {
    aiFile file{};
    RegularFile handle;
    uint64_t position = 0;
};

OpenFile* self(aiFile* f) { return reinterpret_cast<OpenFile*>(f->UserData); }

size_t readProc(aiFile* f, char* buffer, size_t size, size_t count) {
    OpenFile* o = self(f);
    if (size == 0 || count == 0 || o->position >= o->handle.size()) return 0;
    const uint64_t left = o->handle.size() - o->position;
    // Whole elements only, as fread does; `size * count` may overflow for a hostile request.
    const uint64_t elements = std::min<uint64_t>(count, left / size);
    const size_t n = o->handle.readAt(o->position, buffer, size_t(elements * size));
    o->position += n;
    return n / size;
}

size_t writeProc(aiFile*, const char*, size_t, size_t) { return 0; }  // importing never writes
size_t tellProc(aiFile* f) { return size_t(self(f)->position); }
size_t sizeProc(aiFile* f) { return size_t(self(f)->handle.size()); }
void flushProc(aiFile*) {}

aiReturn seekProc(aiFile* f, size_t offset, aiOrigin origin) {
    OpenFile* o = self(f);
    // assimp passes relative offsets as size_t: negative ones wrapped around.
    const int64_t delta = int64_t(offset);
    int64_t base = 0;
    if (origin == aiOrigin_CUR) base = int64_t(o->position);
    else if (origin == aiOrigin_END) base = int64_t(o->handle.size());
    else if (origin != aiOrigin_SET) return aiReturn_FAILURE;
    const int64_t target = origin == aiOrigin_SET ? int64_t(offset) : base + delta;
    if (origin == aiOrigin_SET && offset > uint64_t(std::numeric_limits<int64_t>::max())) return aiReturn_FAILURE;
    if (target < 0 || uint64_t(target) > o->handle.size()) return aiReturn_FAILURE;
    o->position = uint64_t(target);
    return aiReturn_SUCCESS;
}

}  // namespace

GuardedFileSystem::GuardedFileSystem(const std::string& modelPath, const LoadLimits& limits)
    : modelPath_(modelPath), folder_(canonicalFolderOf(modelPath)), limits_(limits) {
    const size_t dot = modelPath.find_last_of('.');
    std::string extension = dot == std::string::npos ? "" : modelPath.substr(dot + 1);
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    objModel_ = extension == "obj";
    io_.OpenProc = &GuardedFileSystem::open;
    io_.CloseProc = &GuardedFileSystem::close;
    io_.UserData = reinterpret_cast<aiUserData>(this);
}

aiFile* GuardedFileSystem::open(aiFileIO* io, const char* path, const char* mode) {
    auto* fs = reinterpret_cast<GuardedFileSystem*>(io->UserData);
    const std::string name = path ? path : "";
    for (const char* m = mode; m && *m; ++m)
        if (*m == 'w' || *m == 'a' || *m == '+') return nullptr;
    struct stat st {};
    if (name.empty() || ::stat(name.c_str(), &st) != 0) return nullptr;  // missing: assimp decides what that means
    auto refuse = [&](const std::string& why) -> aiFile* {
        if (fs->refusal_.empty()) fs->refusal_ = why;
        return nullptr;
    };
    // The model itself may be a symbolic link to elsewhere; what it names must lie beside it.
    if (name != fs->modelPath_ && !fs->limits_.allowOutsidePaths && !isInsideFolder(name, fs->folder_))
        return refuse(outsideFolderMessage(name, fs->modelPath_, fs->folder_));
    auto file = std::make_unique<OpenFile>();
    std::string error;
    if (!file->handle.open(name, fs->limits_.maxFileBytes, &error)) return refuse(error);
    const bool mtl = name.size() > 4 && (name.compare(name.size() - 4, 4, ".mtl") == 0 || name.compare(name.size() - 4, 4, ".MTL") == 0);
    if (name != fs->modelPath_ && (fs->objModel_ || mtl)) {
        std::string text(size_t(file->handle.size()), '\0');
        if (file->handle.readAt(0, text.data(), text.size()) != text.size()) return refuse("'" + name + "' could not be read completely");
        if (!checkMtl(name, text, &error)) return refuse(error);
    }
    file->file.ReadProc = readProc;
    file->file.WriteProc = writeProc;
    file->file.TellProc = tellProc;
    file->file.FileSizeProc = sizeProc;
    file->file.SeekProc = seekProc;
    file->file.FlushProc = flushProc;
    file->file.UserData = reinterpret_cast<aiUserData>(file.get());
    return &file.release()->file;
}

void GuardedFileSystem::close(aiFileIO*, aiFile* file) { delete self(file); }

}  // namespace bricklight::scenes
