// loadModel: a model file under LoadLimits. The cheap checks (a regular file within maxFileBytes) run
// here; the rest (model_checks.h, assimp, the limits on its result) runs in a child process where the
// platform has one, so that whatever assimp does with a hostile file, this process gets an error.
#include "assimp_api.h"
#include "assimp_import.h"
#include "isolated_call.h"
#include "safe_file.h"
#include "scene_geometry.h"
#include "scene_wire.h"

namespace bricklight::scenes {

namespace {

// "cannot load 'path': why", without naming the file twice when `why` starts with it.
std::string cannotLoad(const std::string& path, const std::string& why) {
    const std::string quoted = "'" + path + "'";
    if (why.compare(0, quoted.size(), quoted) != 0) return "cannot load " + quoted + ": " + why;
    const std::string rest = why.substr(quoted.size());  // ": No such file..." or " is a FIFO..."
    if (rest.compare(0, 2, ": ") == 0) return "cannot load " + why;
    return "cannot load " + quoted + ":" + (rest.compare(0, 4, " is ") == 0 ? " it" : "") + rest;
}

}  // namespace

SceneGeometry loadModel(const std::string& path, std::string* error, const LoadLimits& limits) {
    auto fail = [&](const std::string& why) {
        if (error) *error = cannotLoad(path, why);
        return SceneGeometry{};
    };
    std::string why;
    {
        RegularFile file;  // before starting anything: a FIFO, a device or a directory is refused here
        if (!file.open(path, limits.maxFileBytes, &why)) return fail(why);
    }
    // Loaded before fork(): the child must not run the dynamic loader.
    const AssimpApi& api = assimp();
    if (!api.loadError.empty()) return fail(api.loadError);
    SceneGeometry s;
    if (kIsolationAvailable && limits.isolateImport) {
        IsolationLimits isolation;
        isolation.what = "the model importer";
        isolation.timeoutSeconds = limits.importTimeoutSeconds;
        isolation.memoryBytes = limits.importMemoryBytes;
        isolation.maxReplyBytes = maxImportResultBytes(limits);
        isolation.timeoutHint = raiseHint("importTimeoutSeconds");
        isolation.memoryHint = raiseHint("importMemoryBytes");
        std::vector<uint8_t> reply;
        const bool ran = runIsolated(
            [&] {
                std::string childError;
                const SceneGeometry imported = importModelInProcess(path, limits, &childError);
                return encodeImportResult(imported, childError);
            },
            isolation, &reply, &why);
        if (!ran) return fail(why);
        std::string importError;
        if (!decodeImportResult(reply.data(), reply.size(), limits, &s, &importError, &why)) return fail(why);
        if (s.meshes.empty()) return fail(importError);
    } else {
        s = importModelInProcess(path, limits, &why);
        if (s.meshes.empty()) return fail(why);
    }
    s.loadLimits = limits;
    return s;
}

}  // namespace bricklight::scenes
