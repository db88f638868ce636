#include <algorithm>
#include <cctype>

#include "model_checks.h"
#include "safe_file.h"

namespace bricklight::scenes {

namespace {

std::string lowerExtension(const std::string& path) {
    const size_t dot = path.find_last_of('.'), slash = path.find_last_of('/');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return {};
    std::string e = path.substr(dot + 1);
    std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return e;
}

bool readAll(const RegularFile& file, const std::string& path, std::string* bytes, std::string* error) {
    bytes->resize(size_t(file.size()));
    if (file.readAt(0, bytes->data(), bytes->size()) == bytes->size()) return true;
    if (error) *error = "'" + path + "' could not be read completely";
    return false;
}

}  // namespace

bool checkModelFile(const std::string& path, const LoadLimits& limits, std::string* error) {
    RegularFile file;
    if (!file.open(path, limits.maxFileBytes, error)) return false;
    // assimp picks a reader by extension and, failing that, by content: check by both.
    char head[32] = {};
    const size_t headSize = file.readAt(0, head, sizeof head);
    const std::string_view start(head, headSize);
    const std::string extension = lowerExtension(path);
    size_t first = 0;
    if (start.compare(0, 3, "\xEF\xBB\xBF") == 0) first = 3;  // a UTF-8 byte order mark
    while (first < start.size() && std::isspace(static_cast<unsigned char>(start[first]))) ++first;
    std::string bytes;
    // assimp takes a file for PLY by its extension or by a leading "ply" (even "plyly", on which its
    // header reader then spins: found by tests/fuzz/model_import_fuzzer.cpp).
    if (extension == "ply" || start.compare(0, 3, "ply") == 0) {
        return readAll(file, path, &bytes, error) && checkPly(path, bytes, limits, error);
    }
    if (start.compare(0, 4, "glTF") == 0) {
        // The header, the first chunk's header, the JSON chunk (if its claimed length is within the limit:
        // checkGlb refuses it otherwise without needing the bytes) and the next chunk's header.
        std::string prefix(size_t(std::min<uint64_t>(file.size(), 20)), '\0');
        file.readAt(0, prefix.data(), prefix.size());
        if (prefix.size() == 20) {
            const uint64_t jsonLength = uint32_t(uint8_t(prefix[12])) | uint32_t(uint8_t(prefix[13])) << 8 |
                                        uint32_t(uint8_t(prefix[14])) << 16 | uint32_t(uint8_t(prefix[15])) << 24;
            if (jsonLength <= limits.maxJsonBytes) {
                prefix.resize(size_t(std::min<uint64_t>(file.size(), 20 + jsonLength + 8)));
                file.readAt(20, prefix.data() + 20, prefix.size() - 20);
            }
        }
        return checkGlb(path, prefix, file.size(), limits, error);
    }
    if (extension == "gltf" || (first < start.size() && (start[first] == '{' || start[first] == '['))) {
        if (file.size() > limits.maxJsonBytes) {
            if (error)
                *error = "'" + path + "': its JSON is " + std::to_string(file.size()) + " bytes, over the limit of " +
                         std::to_string(limits.maxJsonBytes) + " " + raiseHint("maxJsonBytes");
            return false;
        }
        return readAll(file, path, &bytes, error) && checkGltfJson(path, bytes, limits, error);
    }
    if (extension == "obj") return readAll(file, path, &bytes, error) && checkObj(path, bytes, limits, error);
    return true;
}

}  // namespace bricklight::scenes
