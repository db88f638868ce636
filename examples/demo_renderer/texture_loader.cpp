#include "texture_loader.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <cstring>
#include <vector>

#include "isolated_call.h"
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

// The decoder's output: 8-bit texels of the file's own channels.
struct Decoded {
    uint32_t width = 0, height = 0, channels = 0;
    std::vector<uint8_t> bytes;
};

// Opens and decodes the image, refusing from its header what would cost more than the limits allow.
bool decode(const std::string& path, const std::vector<uint8_t>* encoded, const scenes::LoadLimits& limits, Decoded* out,
            std::string* why) {
    OIIO::Filesystem::IOMemReader memory(encoded ? encoded->data() : nullptr, encoded ? encoded->size() : 0);
    // Colour as stored, not premultiplied by alpha: the alpha is a coverage for the alpha test, and a texel
    // that passes it shows its own colour (premultiplied, texels near the cut-off would darken).
    OIIO::ImageSpec config;
    config.attribute("oiio:UnassociatedAlpha", 1);
    // With a configuration, the readers look for the in-memory file in it (the argument alone went unused:
    // embedded textures failed to open).
    OIIO::Filesystem::IOProxy* proxy = &memory;
    if (encoded) config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
    auto input = OIIO::ImageInput::open(path, &config, encoded ? &memory : nullptr);
    if (!input) return *why = OIIO::geterror(), false;
    // The header alone says what decoding would cost: refuse before allocating for it.
    const OIIO::ImageSpec& spec = input->spec();
    if (spec.width <= 0 || spec.height <= 0 || spec.depth != 1 || spec.nchannels < 1 || spec.nchannels > 64)
        return *why = "its header describes a " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " x " +
                      std::to_string(spec.depth) + " image of " + std::to_string(spec.nchannels) + " channels (not a 2D image)",
               false;
    const uint64_t pixels = uint64_t(spec.width) * uint64_t(spec.height);
    if (pixels > limits.maxTexturePixels)
        return *why = "it is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels, over the limit of " +
                      std::to_string(limits.maxTexturePixels) + " " + scenes::raiseHint("maxTexturePixels"),
               false;
    // A float image's NaN or infinity would become a 0 or 255 texel without a word (a NaN renders black): refused.
    const OIIO::TypeDesc::BASETYPE base = OIIO::TypeDesc::BASETYPE(spec.format.basetype);
    if (base == OIIO::TypeDesc::FLOAT || base == OIIO::TypeDesc::HALF || base == OIIO::TypeDesc::DOUBLE) {
        uint64_t bad = 0;
        if (spec.tile_width == 0) {  // row by row: a float copy of one row, not of the image
            std::vector<float> row(size_t(spec.width) * size_t(spec.nchannels));
            for (int y = 0; y < spec.height; ++y) {
                if (!input->read_scanline(y, 0, OIIO::TypeDesc::FLOAT, row.data())) return *why = input->geterror(), false;
                for (float v : row) bad += !std::isfinite(v);
            }
        } else {
            std::vector<float> all(size_t(pixels) * size_t(spec.nchannels));
            if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, all.data())) return *why = input->geterror(), false;
            for (float v : all) bad += !std::isfinite(v);
        }
        if (bad)
            return *why = "it holds " + std::to_string(bad) + " values that are not finite (NaN or infinite) of " +
                          std::to_string(pixels * uint64_t(spec.nchannels)),
                   false;
    }
    out->width = uint32_t(spec.width);
    out->height = uint32_t(spec.height);
    out->channels = uint32_t(spec.nchannels);
    out->bytes.resize(size_t(pixels) * out->channels);
    if (!input->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT8, out->bytes.data())) return *why = input->geterror(), false;
    input->close();
    return true;
}

// The decoder in a child process (isolated_call.h) where the platform allows: the image readers are
// third-party code that a hostile file could crash or hang. The reply is 1 + width, height, channels
// (uint32 each) + texels, or 0 + the reason.
bool decodeIsolated(const std::string& path, const std::vector<uint8_t>* encoded, const scenes::LoadLimits& limits, Decoded* out,
                    std::string* why) {
    scenes::IsolationLimits isolation;
    isolation.what = "the image decoder";
    isolation.timeoutSeconds = limits.importTimeoutSeconds;
    isolation.memoryBytes = limits.importMemoryBytes;
    isolation.maxReplyBytes = 13 + limits.maxTexturePixels * 64 + 4096;
    isolation.timeoutHint = scenes::raiseHint("importTimeoutSeconds");
    isolation.memoryHint = scenes::raiseHint("importMemoryBytes");
    std::vector<uint8_t> reply;
    const bool ran = scenes::runIsolated(
        [&] {
            Decoded d;
            std::string reason;
            std::vector<uint8_t> r;
            if (!decode(path, encoded, limits, &d, &reason)) {
                r.push_back(0);
                r.insert(r.end(), reason.begin(), reason.end());
                return r;
            }
            r.resize(13);
            r[0] = 1;
            const uint32_t header[3] = {d.width, d.height, d.channels};
            std::memcpy(r.data() + 1, header, sizeof header);
            r.insert(r.end(), d.bytes.begin(), d.bytes.end());
            return r;
        },
        isolation, &reply, why);
    if (!ran) return false;
    if (reply.empty()) return *why = "the image decoder sent no reply", false;
    if (reply[0] == 0) return *why = std::string(reply.begin() + 1, reply.end()), false;
    uint32_t header[3] = {};
    if (reply.size() < 13) return *why = "the image decoder's reply is cut short", false;
    std::memcpy(header, reply.data() + 1, sizeof header);
    const uint64_t expected = uint64_t(header[0]) * header[1] * header[2];
    if (header[2] == 0 || header[2] > 64 || uint64_t(header[0]) * header[1] > limits.maxTexturePixels || reply.size() - 13 != expected)
        return *why = "the image decoder's reply does not match its header", false;
    out->width = header[0];
    out->height = header[1];
    out->channels = header[2];
    out->bytes.assign(reply.begin() + 13, reply.end());
    return true;
}

}  // namespace

bool loadTextureLayer(const std::string& path, uint32_t size, std::vector<uint8_t>* texels, std::string* error,
                      const std::vector<uint8_t>* encoded, const scenes::LoadLimits& limits, bool coverage) {
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
    Decoded decoded;
    const bool isolated = scenes::kIsolationAvailable && limits.isolateImport;
    if (!(isolated ? decodeIsolated(path, encoded, limits, &decoded, &why) : decode(path, encoded, limits, &decoded, &why)))
        return fail(why);
    const int channels = int(decoded.channels);
    OIIO::ImageSpec decodedSpec(int(decoded.width), int(decoded.height), channels, OIIO::TypeDesc::UINT8);
    OIIO::ImageBuf source(decodedSpec, decoded.bytes.data());
    // Grey and grey-alpha to RGBA, RGB to RGBA (alpha 1; a coverage map's alpha: its first channel).
    const int alpha = channels == 4 ? 3 : channels == 2 ? 1 : coverage ? 0 : -1;
    const int map[4] = {0, channels >= 3 ? 1 : 0, channels >= 3 ? 2 : 0, alpha};
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
