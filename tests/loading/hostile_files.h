// Model and texture files that once crashed, hung or misled bricklight-render (issue 23), and small valid
// ones to compare with, written at test time (the big and deep ones would not belong in the repository).
// Used by bricklight-loading-tests and, through bricklight-hostile-files, by cli_rejects_hostile_files.sh.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bricklight::testing {

struct HostileFile {
    std::string name;     // a short id: "ply-face255-binary"
    std::string path;     // what to load
    std::string message;  // a regular expression the refusal must match
    std::string what;     // the case, for reports
    bool texture = false;  // the model loads; its texture is refused (when the renderer reads it)
};

// Writes every case under `folder` (created; one subfolder per case, so that each model's folder holds
// only its own files) and returns them.
std::vector<HostileFile> writeHostileFiles(const std::string& folder);

// Files for building cases.
bool writeFile(const std::string& path, const std::string& bytes);
// A PNG of `width` x `height` RGB pixels whose image data holds only the first `rows` rows (all grey).
std::string pngBytes(uint32_t width, uint32_t height, uint32_t rows);
// A triangle with texture coordinates, base colour texture `textureUri`: a glTF whose buffer is the
// file `bufferName` beside it (written too), or `bufferUri` as given.
std::string gltfTriangle(const std::string& textureUri, const std::string& bufferUri, const std::string& extraTopLevel = "");
std::string triangleBuffer();  // the binary buffer gltfTriangle's accessors read
// A GLB of gltfTriangle whose texture is `png`, embedded.
std::string glbTriangle(const std::string& png);
// An OBJ triangle with texture coordinates using material "m" from `mtl`.
std::string objTriangle(const std::string& mtl);

}  // namespace bricklight::testing
