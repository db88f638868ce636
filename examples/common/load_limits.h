// What loading a model file, and the files it references, may cost. Model files come from anywhere:
// every count a file states is checked against these before the work it would cause, and a file over a
// limit is refused with a message naming the file, the limit and the option that raises it.
#pragma once

#include <cstdint>
#include <string>

namespace bricklight::scenes {

struct LoadLimits {
    // Bytes of the model file and of each file it references (glTF buffers, MTL files, textures).
    uint64_t maxFileBytes = 1ull << 30;  // 1 GiB
    // Bytes of glTF's JSON: a .gltf file, or a GLB's JSON chunk (also checked against the GLB's size).
    uint64_t maxJsonBytes = 64ull << 20;  // 64 MiB
    // Nesting of JSON arrays and objects (glTF needs about 8; the parser recurses per level).
    uint32_t maxJsonDepth = 128;
    // Vertices over all meshes, and vertex indices over all faces (3 per triangle).
    uint64_t maxVertices = 20'000'000;
    uint64_t maxIndices = 60'000'000;
    // Indices of one face before triangulation (a polygon's corners).
    uint32_t maxFaceIndices = 1024;
    // Nodes of the scene graph, and how deep it nests (the importer recurses per level).
    uint64_t maxNodes = 1'000'000;
    uint32_t maxNodeDepth = 256;
    // Width x height (x depth) of one texture, read from its header before it is decoded: 8192 x 8192
    // (decoded as RGBA8: 256 MiB).
    uint64_t maxTexturePixels = 8192ull * 8192ull;
    // Files a model references (buffers, MTL files, textures) must lie inside the model's folder, after
    // resolving symbolic links; true allows any path.
    bool allowOutsidePaths = false;
    // The importer runs in a child process (Linux; see isolated_call.h): its wall-clock limit and how
    // much address space it may add to what it inherits.
    double importTimeoutSeconds = 60.0;
    uint64_t importMemoryBytes = 4ull << 30;  // 4 GiB
    // false: import in this process (no protection against the importer crashing or hanging; what
    // platforms without fork() always do). For fuzzing the importer and debugging.
    bool isolateImport = true;
};

// "(raise it with --max-node-depth, LoadLimits::maxNodeDepth)": how a message names the limit that
// refused a file. `field` is the LoadLimits member; the option is bricklight-render's.
std::string raiseHint(const char* field);

}  // namespace bricklight::scenes
