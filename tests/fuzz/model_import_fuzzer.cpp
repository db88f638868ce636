// libFuzzer target: model files through loadModel, as bricklight-render loads them. An input is
//   byte 0: the format (the file's extension, from kFormats), or one past the list: the rest is an
//           out-of-process importer's reply, straight into decodeImportResult (the trust boundary);
//   the rest: the file; where "\n@@2@@\n" occurs, what follows is a second file beside it (the MTL of an
//           OBJ, named model.mtl; the buffer of a glTF, named buffer.bin).
// Our own code runs in this process, instrumented: checkModelFile and checkMtl (the checks before and
// around assimp) and the decoding of the importer's reply. assimp itself (not instrumented) runs out of process, as in the
// product, so that its crashes and hangs are the clean errors this target asserts on; those are noted on
// stderr ("model_import_fuzzer: importer ...") for the record. BRICKLIGHT_FUZZ_IN_PROCESS=1 runs assimp in
// this process instead, for hunting assimp's own bugs (then they are findings we can only guard against).
// Traps: an error that does not start with "cannot load '<path>'", a loaded scene with an index past its
// vertices or more vertices than the limits allow.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include "model_checks.h"
#include "scene_geometry.h"
#include "scene_wire.h"

namespace {

using namespace bricklight::scenes;

const char* const kFormats[] = {"obj", "ply", "gltf", "glb", "stl", "off", "dae", "fbx", "3ds", "x", "ac", "ase", "lwo", "md2", "nff", "smd"};
constexpr size_t kFormatCount = sizeof kFormats / sizeof kFormats[0];

const std::string& folder() {
    static const std::string dir = [] {
        std::string pattern = (std::filesystem::temp_directory_path() / "model_import_fuzzer.XXXXXX").string();
        if (!mkdtemp(pattern.data())) std::abort();
        return pattern;
    }();
    return dir;
}

void write(const std::string& path, std::string_view bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(bytes.data(), std::streamsize(bytes.size()));
}

LoadLimits fuzzLimits() {
    // Well inside libFuzzer's -timeout=10 and -rss_limit_mb=2048 (the child's memory is its own).
    LoadLimits limits;
    limits.importTimeoutSeconds = 4.0;
    limits.importMemoryBytes = 1ull << 30;
    limits.maxVertices = 1u << 20;
    limits.maxIndices = 3u << 20;
    static const bool inProcess = std::getenv("BRICKLIGHT_FUZZ_IN_PROCESS") && std::string(std::getenv("BRICKLIGHT_FUZZ_IN_PROCESS")) == "1";
    limits.isolateImport = !inProcess;
    return limits;
}

void checkScene(const SceneGeometry& s, const LoadLimits& limits) {
    uint64_t vertices = 0;
    for (const TriangleMesh& m : s.meshes) {
        vertices += m.positions.size() / 3;
        for (uint32_t index : m.indices)
            if (index >= m.positions.size() / 3) __builtin_trap();
        if (!m.uvs.empty() && m.uvs.size() != 2 * (m.positions.size() / 3)) __builtin_trap();
    }
    for (const MeshInstance& i : s.instances)
        if (i.mesh >= s.meshes.size()) __builtin_trap();
    if (vertices > limits.maxVertices + 4 * s.pointLights.size() + 4 * 64) __builtin_trap();  // area lights add quads
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const LoadLimits limits = fuzzLimits();
    const size_t format = data[0] % (kFormatCount + 1);
    const std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
    if (format == kFormatCount) {
        SceneGeometry s;
        std::string importError, error;
        if (decodeImportResult(data + 1, size - 1, limits, &s, &importError, &error)) checkScene(s, limits);
        return 0;
    }
    const std::string path = folder() + "/model." + kFormats[format];
    const size_t split = rest.find("\n@@2@@\n");
    write(path, rest.substr(0, split));
    const std::string companion = folder() + (format == 0 ? "/model.mtl" : format <= 3 ? "/buffer.bin" : "/companion.bin");
    if (split != std::string_view::npos) write(companion, rest.substr(split + 7));
    else std::filesystem::remove(companion);

    std::string error;
    // Our checks, in this process (they also run in the importer's child): whatever they answer, no crash.
    checkModelFile(path, limits, &error);
    if (format == 0 && split != std::string_view::npos) checkMtl(companion, rest.substr(split + 7), &error);
    const SceneGeometry s = loadModel(path, &error, limits);
    if (s.meshes.empty()) {
        const std::string prefix = "cannot load '" + path + "'";
        if (error.rfind(prefix, 0) != 0) __builtin_trap();
        // What the child reported about itself (not what a file's own text might say).
        for (const char* what : {": the model importer crashed (", ": the model importer timed out", ": the model importer exceeded"})
            if (error.compare(prefix.size(), std::strlen(what), what) == 0)
                std::fprintf(stderr, "model_import_fuzzer: importer (.%s): %s\n", kFormats[format], error.c_str() + prefix.size() + 2);
        return 0;
    }
    checkScene(s, limits);
    return 0;
}
