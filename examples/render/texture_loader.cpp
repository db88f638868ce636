#include "texture_loader.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>

namespace bricklight::render {

bool loadTextureLayer(const std::string& path, uint32_t size, std::vector<uint8_t>* texels, std::string* error,
                      const std::vector<uint8_t>* encoded) {
    OIIO::Filesystem::IOMemReader memory(encoded ? encoded->data() : nullptr, encoded ? encoded->size() : 0);
    OIIO::ImageBuf source = encoded ? OIIO::ImageBuf(path, 0, 0, nullptr, nullptr, &memory) : OIIO::ImageBuf(path);
    if (!source.read(0, 0, true, OIIO::TypeDesc::UINT8)) {
        if (error) *error = "'" + path + "' cannot be loaded: " + source.geterror();
        return false;
    }
    const int channels = source.nchannels();
    if (channels < 1) {
        if (error) *error = "'" + path + "' has no channels";
        return false;
    }
    // Grey and grey-alpha to RGBA, RGB to RGBA (alpha 1).
    const int map[4] = {0, channels >= 3 ? 1 : 0, channels >= 3 ? 2 : 0, channels == 4 ? 3 : (channels == 2 ? 1 : -1)};
    const float fill[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    OIIO::ImageBuf rgba = OIIO::ImageBufAlgo::channels(source, 4, map, fill);
    OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(rgba, "", 0.0f, OIIO::ROI(0, int(size), 0, int(size), 0, 1, 0, 4));
    if (resized.has_error() || rgba.has_error()) {
        if (error) *error = "'" + path + "' cannot be resampled: " + resized.geterror() + rgba.geterror();
        return false;
    }
    const size_t offset = texels->size();
    texels->resize(offset + size_t(size) * size * 4);
    if (!resized.get_pixels(OIIO::ROI(0, int(size), 0, int(size), 0, 1, 0, 4), OIIO::TypeDesc::UINT8, texels->data() + offset)) {
        if (error) *error = "'" + path + "': " + resized.geterror();
        return false;
    }
    return true;
}

}  // namespace bricklight::render
