// Image files in a build without OpenImageIO (BRICKLIGHT_OPENIMAGEIO=OFF, e.g. for a GPU machine that has
// only drivers): every call fails with a message that says so. The renderer itself works; scenes with
// base-colour textures are refused at load, like any texture that cannot be read.
#include "image_io.h"
#include "texture_loader.h"

namespace bricklight::render {

namespace {
bool unavailable(const std::string& path, std::string* error) {
    if (error) *error = "'" + path + "': this build has no image files (configured with BRICKLIGHT_OPENIMAGEIO=OFF)";
    return false;
}
}  // namespace

bool writeImage(const std::string& path, const Image&, float, std::string* error) { return unavailable(path, error); }
bool readImage(const std::string& path, Image*, std::string* error, const scenes::LoadLimits&) { return unavailable(path, error); }
bool writeDisplayImage(const std::string& path, uint32_t, uint32_t, const std::vector<uint8_t>&, std::string* error) {
    return unavailable(path, error);
}
bool loadTextureLayer(const std::string& path, uint32_t, std::vector<uint8_t>*, std::string* error, const std::vector<uint8_t>*,
                      const scenes::LoadLimits&, bool) {
    return unavailable(path, error);
}

}  // namespace bricklight::render
