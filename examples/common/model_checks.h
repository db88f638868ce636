// Checks of a model file before assimp reads it: what the file's own structure says it holds (element
// counts, list lengths, chunk lengths, JSON nesting, node hierarchies, referenced names), against
// LoadLimits, in time and memory proportional to the file. Each returns false with `error` naming the
// file, the problem and, for a limit, how to raise it. Formats without a check here rely on the import
// running out of process (isolated_call.h) and on the limits applied to its result.
#pragma once

#include <string>
#include <string_view>

#include "load_limits.h"

namespace bricklight::scenes {

// Picks the check by content (PLY's "ply", GLB's "glTF", JSON's '{') or extension (.obj, .gltf).
bool checkModelFile(const std::string& path, const LoadLimits& limits, std::string* error);

// PLY: a header that ends (end_header), element counts within the limits and the file, every list within
// maxFaceIndices and inside the file (binary) or its line (ASCII), vertex indices in range.
bool checkPly(const std::string& path, std::string_view bytes, const LoadLimits& limits, std::string* error);
// GLB: a header and chunk lengths that fit the file (`fileSize` bytes), a JSON chunk within maxJsonBytes,
// then checkGltfJson. `prefix`: the file's first bytes, at least through the JSON chunk where it fits.
bool checkGlb(const std::string& path, std::string_view prefix, uint64_t fileSize, const LoadLimits& limits, std::string* error);
// glTF's JSON: nesting within maxJsonDepth (before parsing), then nodes (count, a tree, depth), accessor
// counts and the vertices and indices the node instances add up to, buffer sizes, image URIs that assimp
// can hold (not empty, at most 1023 characters), alphaMode one of glTF's three names and alphaCutoff a number.
bool checkGltfJson(const std::string& path, std::string_view json, const LoadLimits& limits, std::string* error);
// OBJ: vertices and face corners within the limits, faces within maxFaceIndices.
bool checkObj(const std::string& path, std::string_view bytes, const LoadLimits& limits, std::string* error);
// MTL (GuardedFileSystem checks each file an OBJ import opens): texture names that assimp can hold (at
// most 1023 characters), no texture before the first newmtl.
bool checkMtl(const std::string& path, std::string_view text, std::string* error);

// The nesting depth of arrays and objects in `json`, counting no further than `limit + 1` (strings
// skipped; no recursion, so any depth is safe to measure).
uint64_t jsonNestingDepth(std::string_view json, uint64_t limit);

// assimp keeps names (aiString) of at most this many characters and drops longer texture names silently.
constexpr size_t kAssimpMaxName = 1023;

}  // namespace bricklight::scenes
