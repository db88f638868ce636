#include "texture_loader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include "safe_file.h"

namespace bricklight::render {

namespace {

// A refusal from scenes::RegularFile ("'path' is a device, ...") as the rest of "'path' cannot be loaded: ...".
std::string reasonWithoutPath(const std::string& why, const std::string& path) {
    const std::string quoted = "'" + path + "'";
    if (why.compare(0, quoted.size(), quoted) != 0) return why;
    std::string rest = why.substr(quoted.size());
    if (rest.compare(0, 2, ": ") == 0) return rest.substr(2);
    if (rest.compare(0, 1, " ") == 0) return "it" + rest;
    return rest;
}

}  // namespace

bool loadTextureLayer(const std::string& path, uint32_t size, std::vector<uint8_t>* texels, std::string* error,
                      const std::vector<uint8_t>* encoded, const scenes::LoadLimits& limits) {
    auto fail = [&](const std::string& why) {
        if (error) *error = "'" + path + "' cannot be loaded: " + why;
        return false;
    };
    std::string why;
    if (!encoded) {
        // Not /dev/zero, a FIFO or a directory: OpenImageIO probes every reader on such a "file", forever.
        scenes::RegularFile file;
        if (!file.open(path, limits.maxFileBytes, &why)) return fail(reasonWithoutPath(why, path));
    } else if (encoded->size() > limits.maxFileBytes) {
        return fail("its " + std::to_string(encoded->size()) + " bytes are over the limit of " + std::to_string(limits.maxFileBytes) + " " +
                    scenes::raiseHint("maxFileBytes"));
    }
    OIIO::Filesystem::IOMemReader memory(encoded ? encoded->data() : nullptr, encoded ? encoded->size() : 0);
    auto input = OIIO::ImageInput::open(path, nullptr, encoded ? &memory : nullptr);
    if (!input) return fail(OIIO::geterror());
    // The header alone says what decoding would cost: refuse before allocating for it.
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels < 1 || spec.nchannels > 64)
        return fail("its header describes a " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " x " +
                    std::to_string(spec.depth) + " image of " + std::to_string(spec.nchannels) + " channels (not a 2D image)");
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
    if (pixels > limits.maxTexturePixels)
        return fail("it is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels, over the limit of " +
                    std::to_string(limits.maxTexturePixels) + " " + scenes::raiseHint("maxTexturePixels"));
    const int channels = spec.nchannels;
    OIIO::ImageSpec decodedSpec(spec.width, spec.height, channels, OIIO::TypeDesc::UINT8);
    std::vector<uint8_t> decoded(size_t(pixels) * size_t(channels));
    if (!input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, decoded.data())) return fail(input->geterror());
    input->close();
    OIIO::ImageBuf source(decodedSpec, decoded.data());
    // Grey and grey-alpha to RGBA, RGB to RGBA (alpha 1).
    const int map[4] = {0, channels >= 3 ? 1 : 0, channels >= 3 ? 2 : 0, channels == 4 ? 3 : (channels == 2 ? 1 : -1)};
    const float fill[4] = {0.0f, 0.0f, 0.0f, 1.0f};
    OIIO::ImageBuf rgba = OIIO::ImageBufAlgo::channels(source, 4, map, fill);
    OIIO::ImageBuf resized = OIIO::ImageBufAlgo::resize(rgba, "", 0.0f, OIIO::ROI(0, int(size), 0, int(size), 0, 1, 0, 4));
    if (resized.has_error() || rgba.has_error()) return fail("it cannot be resampled: " + resized.geterror() + rgba.geterror());
    const size_t offset = texels->size();
    texels->resize(offset + size_t(size) * size * 4);
    if (!resized.get_pixels(OIIO::ROI(0, int(size), 0, int(size), 0, 1, 0, 4), OIIO::TypeDesc::UINT8, texels->data() + offset)) {
        texels->resize(offset);
        return fail(resized.geterror());
    }
    return true;
}

}  // namespace bricklight::render
