// The file system assimp sees while it imports a model: every file it opens (the model, glTF buffers,
// MTL files, ...) must be a regular file within LoadLimits::maxFileBytes and, unless allowOutsidePaths,
// lie inside the model's folder. assimp reports a refused file only as "cannot open": the refusal is kept
// here and fails the import with its own message, even where assimp would have gone on without the file.
// The files an OBJ import opens besides the model are MTL files (named by mtllib, or the model's name
// with .mtl when that one is missing): each is read here first and checked (checkMtl), so that what
// assimp reads is what was checked.
#pragma once

#include <assimp/cfileio.h>

#include <string>

#include "load_limits.h"

namespace bricklight::scenes {

class GuardedFileSystem {
public:
    GuardedFileSystem(const std::string& modelPath, const LoadLimits& limits);
    GuardedFileSystem(const GuardedFileSystem&) = delete;
    GuardedFileSystem& operator=(const GuardedFileSystem&) = delete;
    aiFileIO* io() { return &io_; }
    // The first file refused for what it is or where it lies (a missing file is not a refusal); empty if none.
    const std::string& refusal() const { return refusal_; }

private:
    static aiFile* open(aiFileIO* io, const char* path, const char* mode);
    static void close(aiFileIO* io, aiFile* file);

    aiFileIO io_{};
    std::string modelPath_;
    std::string folder_;  // the model's folder, symbolic links resolved
    bool objModel_ = false;
    LoadLimits limits_;
    std::string refusal_;
};

}  // namespace bricklight::scenes
