#include "image_io.h"
#include "image_encoding.h"
#include "output_file.h"
#include "safe_file.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace bricklight::render {

const char* floatImageExtension() { return "exr"; }

namespace {

// Encodes `image` into `path` (whose extension picks the format).
bool encodeImage(const std::string& path, const Image& image, float exposure, std::string* error) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        if (error) *error = OIIO::geterror();
        return false;
    }
    bool ok;
    if (imageExtension(path) == "exr") {
        OIIO::ImageSpec spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::FLOAT);
        ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data());
    } else {
        std::vector<uint8_t> bytes(image.rgb.size());
        for (size_t i = 0; i < bytes.size(); ++i)
            bytes[i] = displayByte(image.rgb[i], exposure);
        OIIO::ImageSpec spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::UINT8);
        ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    }
    ok = out->close() && ok;  // close() flushes: a full disk shows here
    if (!ok && error) *error = out->geterror();  // may be empty: the caller adds errno
    return ok;
}

}  // namespace

bool writeImage(const std::string& path, const Image& image, float exposure, std::string* error) {
    if (!checkImageToWrite(path, image, error)) return false;
    // The file is read back whole before it replaces the target: a write that failed silently (a full
    // disk some encoders do not report) is caught here.
    auto readsBack = [&](const std::string& temp, std::string* why) {
        Image back;
        if (!readImage(temp, &back, why)) return false;
        if (back.width != image.width || back.height != image.height) {
            *why = "the written file reads back as " + std::to_string(back.width) + "x" + std::to_string(back.height);
            return false;
        }
        return true;
    };
    return writeFileAtomically(
        path, [&](const std::string& temp, std::string* why) { return encodeImage(temp, image, exposure, why); }, readsBack, error);
}

bool writeDisplayImage(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba,
                       std::string* error) {
    if (!checkDisplayImageToWrite(path, width, height, rgba, error)) return false;
    auto encode = [&](const std::string& temp, std::string* why) {
        auto out = OIIO::ImageOutput::create(temp);
        if (!out) {
            *why = OIIO::geterror();
            return false;
        }
        // RGB of the RGBA bytes: OpenImageIO strides over the alpha.
        OIIO::ImageSpec spec(int(width), int(height), 3, OIIO::TypeDesc::UINT8);
        bool ok = out->open(temp, spec) &&
                  out->write_image(OIIO::TypeDesc::UINT8, rgba.data(), 4, OIIO::stride_t(width) * 4, OIIO::AutoStride);
        ok = out->close() && ok;
        if (!ok) *why = out->geterror();
        return ok;
    };
    auto readsBack = [&](const std::string& temp, std::string* why) {
        Image back;
        if (!readImage(temp, &back, why)) return false;
        if (back.width != width || back.height != height) {
            *why = "the written file reads back as " + std::to_string(back.width) + "x" + std::to_string(back.height);
            return false;
        }
        return true;
    };
    return writeFileAtomically(path, encode, readsBack, error);
}

bool readImage(const std::string& path, Image* image, std::string* error, const scenes::LoadLimits& limits) {
    // Not a FIFO, /dev/zero or a directory (OpenImageIO probes every reader on them, forever), nor a file
    // over the size limit.
    std::string why;
    scenes::RegularFile file;
    if (!file.open(path, limits.maxFileBytes, &why)) {
        if (error) *error = why;
        return false;
    }
    auto in = OIIO::ImageInput::open(path);
    if (!in) {
        if (error) *error = "cannot read '" + path + "': " + OIIO::geterror();
        return false;
    }
    // The header says what decoding would cost: refused before anything is allocated for it.
    const OIIO::ImageSpec& spec = in->spec();
    if (spec.nchannels < 1 || spec.nchannels > 64 || spec.width <= 0 || spec.height <= 0 || spec.depth != 1) {
        if (error)
            *error = "'" + path + "': its header describes a " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " x " +
                     std::to_string(spec.depth) + " image of " + std::to_string(spec.nchannels) + " channels (not a 2D image)";
        return false;
    }
    const uint64_t pixelCount = uint64_t(spec.width) * uint64_t(spec.height);
    if (pixelCount > limits.maxTexturePixels) {
        if (error)
            *error = "'" + path + "' is " + std::to_string(spec.width) + " x " + std::to_string(spec.height) + " pixels, over the limit of " +
                     std::to_string(limits.maxTexturePixels) + " (LoadLimits::maxTexturePixels)";
        return false;
    }
    std::vector<float> pixels(size_t(pixelCount) * spec.nchannels);
    if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, pixels.data())) {
        if (error) *error = "cannot read '" + path + "': " + in->geterror();
        return false;
    }
    const bool linear = spec.format == OIIO::TypeDesc::FLOAT || spec.format == OIIO::TypeDesc::HALF;
    image->width = uint32_t(spec.width);
    image->height = uint32_t(spec.height);
    image->rgb.resize(size_t(spec.width) * spec.height * 3);
    for (size_t p = 0; p < size_t(spec.width) * spec.height; ++p)
        for (int c = 0; c < 3; ++c) {
            const float v = pixels[p * spec.nchannels + size_t(std::min(c, spec.nchannels - 1))];
            image->rgb[3 * p + size_t(c)] = linear ? v : linearFromSrgb(v);
        }
    return true;
}

}  // namespace bricklight::render
