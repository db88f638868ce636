// OBJ before assimp: the counts it will build (assimp makes a vertex per face corner) and polygons within
// maxFaceIndices. MTL files, as assimp opens them (GuardedFileSystem): texture names assimp drops silently
// when they are longer than it can hold (a 5000-character name gave an untextured model and no message),
// and textures before any material, on which assimp 5.2 crashes.
#include <algorithm>
#include <vector>

#include "model_checks.h"

namespace bricklight::scenes {

namespace {

std::string_view trim(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
    return s;
}

// Calls `line(number, keyword, rest)` for each line; stops when it returns false.
template <typename F>
bool forEachLine(std::string_view text, F&& line) {
    size_t pos = 0, number = 0;
    while (pos < text.size()) {
        size_t end = text.find('\n', pos);
        if (end == std::string_view::npos) end = text.size();
        const std::string_view l = trim(text.substr(pos, end - pos));
        pos = end + 1;
        ++number;
        size_t split = 0;
        while (split < l.size() && l[split] != ' ' && l[split] != '\t') ++split;
        if (!line(number, l.substr(0, split), trim(l.substr(split)))) return false;
    }
    return true;
}

size_t wordCount(std::string_view s) {
    size_t n = 0;
    for (size_t i = 0; i < s.size();) {
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
        if (i < s.size()) ++n;
        while (i < s.size() && s[i] != ' ' && s[i] != '\t') ++i;
    }
    return n;
}

// By prefix, as assimp's MTL reader compares them (a keyword "bump\x01" is a bump map to it).
bool isTextureStatement(std::string_view keyword) {
    for (const char* prefix : {"map_", "bump", "disp", "decal", "refl", "norm"})
        if (keyword.rfind(prefix, 0) == 0) return true;
    return false;
}

}  // namespace

bool checkMtl(const std::string& mtlPath, std::string_view text, std::string* error) {
    size_t pos = 0, start = 0;
    auto fail = [&](const std::string& why) {
        const size_t number = 1 + size_t(std::count(text.begin(), text.begin() + long(start), '\n'));
        if (error) *error = "'" + mtlPath + "' line " + std::to_string(number) + ": " + why;
        return false;
    };
    // assimp 5.2 writes statements into the current material, which is null before the first newmtl: some
    // crash it ("map_Kd", "bump", "a": SIGSEGV, found by tests/fuzz/model_import_fuzzer.cpp). Only blank
    // lines and comments may come first; a NUL or CR ends a line here as it may for assimp's reader.
    bool material = false;
    while (pos < text.size()) {
        size_t end = text.find_first_of(std::string_view("\n\r\0", 3), pos);
        if (end == std::string_view::npos) end = text.size();
        start = pos;
        const std::string_view line = trim(text.substr(pos, end - pos));
        pos = end + 1;
        size_t split = 0;
        while (split < line.size() && line[split] != ' ' && line[split] != '\t') ++split;
        const std::string_view keyword = line.substr(0, split), rest = trim(line.substr(split));
        if (keyword == "newmtl") material = true;
        if (line.empty() || line[0] == '#' || material) {
            // Options and name together: assimp reads the name into a string of at most kAssimpMaxName.
            if (isTextureStatement(keyword) && rest.size() > kAssimpMaxName)
                return fail("the texture name is " + std::to_string(rest.size()) + " characters; assimp keeps at most " +
                                        std::to_string(kAssimpMaxName) + " and would drop the texture");
            continue;
        }
        return fail("'" + std::string(keyword.substr(0, 32)) + "' before any newmtl (assimp cannot read it)");
    }
    return true;
}

bool checkObj(const std::string& path, std::string_view bytes, const LoadLimits& limits, std::string* error) {
    uint64_t positions = 0, corners = 0;
    return forEachLine(bytes, [&](size_t number, std::string_view keyword, std::string_view rest) {
        auto fail = [&](const std::string& why) {
            if (error) *error = "'" + path + "' line " + std::to_string(number) + ": " + why;
            return false;
        };
        if (keyword == "v") {
            if (++positions > limits.maxVertices)
                return fail("more than " + std::to_string(limits.maxVertices) + " vertices " + raiseHint("maxVertices"));
        } else if (keyword == "f" || keyword == "l" || keyword == "p") {
            const size_t n = wordCount(rest);
            if (keyword == "f" && n > limits.maxFaceIndices)
                return fail("a face of " + std::to_string(n) + " corners, over the limit of " + std::to_string(limits.maxFaceIndices) + " " +
                            raiseHint("maxFaceIndices"));
            corners += n;
            // assimp makes one vertex per corner, so the corners bound both counts.
            if (corners > limits.maxIndices)
                return fail("the faces have more than " + std::to_string(limits.maxIndices) + " corners " + raiseHint("maxIndices"));
            if (corners > limits.maxVertices)
                return fail("the faces have more than " + std::to_string(limits.maxVertices) + " corners (a vertex each) " +
                            raiseHint("maxVertices"));
        }
        return true;
    });
}

}  // namespace bricklight::scenes
