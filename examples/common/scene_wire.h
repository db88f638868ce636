// The imported scene as bytes, for the out-of-process importer's reply: a small length-checked binary
// format (a magic number and version, then counts before arrays, in host byte order: both ends are the
// same program). The decoder is where an importer subverted by a hostile
// file meets this process: every count is checked against the bytes that remain and against LoadLimits
// before anything is allocated, and every reference (instance -> mesh, index -> vertex, mesh -> embedded
// texture) is checked, so a malformed reply is an error, never a crash or an unbounded allocation.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene_geometry.h"

namespace bricklight::scenes {

// The import's outcome: the scene's model content (meshes, instances, bounds, environment, lights,
// camera, warnings; not `animate` or `loadLimits`), or the error.
std::vector<uint8_t> encodeImportResult(const SceneGeometry& scene, const std::string& error);
// False with `error` ("the model importer's reply is malformed: ...") if the bytes are not a reply;
// otherwise true with either `scene` filled or `importError` set (the import failed).
bool decodeImportResult(const uint8_t* bytes, size_t size, const LoadLimits& limits, SceneGeometry* scene, std::string* importError,
                        std::string* error);
// The most bytes a reply within `limits` can take (what the parent reads at most).
uint64_t maxImportResultBytes(const LoadLimits& limits);

}  // namespace bricklight::scenes
