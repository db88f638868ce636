#include "image_io.h"
#include "output_file.h"
#include "safe_file.h"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

namespace bricklight::render {

namespace {

std::string extensionOf(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

float filmic(float x) {  // ACES approximation (K. Narkowicz 2015), input already exposed
    x = std::max(0.0f, x);
    return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

float toSrgb(float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }
float fromSrgb(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

// Encodes `image` into `path` (whose extension picks the format).
bool encodeImage(const std::string& path, const Image& image, float exposure, std::string* error) {
    auto out = OIIO::ImageOutput::create(path);
    if (!out) {
        if (error) *error = OIIO::geterror();
        return false;
    }
    bool ok;
    if (extensionOf(path) == "exr") {
        OIIO::ImageSpec spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::FLOAT);
        ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::FLOAT, image.rgb.data());
    } else {
        std::vector<uint8_t> bytes(image.rgb.size());
        for (size_t i = 0; i < bytes.size(); ++i)
            bytes[i] = uint8_t(std::lround(toSrgb(filmic(image.rgb[i] * exposure)) * 255.0f));
        OIIO::ImageSpec spec(int(image.width), int(image.height), 3, OIIO::TypeDesc::UINT8);
        ok = out->open(path, spec) && out->write_image(OIIO::TypeDesc::UINT8, bytes.data());
    }
    ok = out->close() && ok;  // close() flushes: a full disk shows here
    if (!ok && error) *error = out->geterror();  // may be empty: the caller adds errno
    return ok;
}

}  // namespace

bool writeImage(const std::string& path, const Image& image, float exposure, std::string* error) {
    const std::string ext = extensionOf(path);
    if (ext != "png" && ext != "exr") {
        if (error) *error = "'" + path + "': unsupported output format (use .png or .exr)";
        return false;
    }
    if (image.width == 0 || image.height == 0 || image.rgb.size() != size_t(image.width) * image.height * 3) {
        if (error) *error = "'" + path + "': no image to write";
        return false;
    }
    // A pixel that is infinite or NaN would make every comparison against the file silently wrong.
    size_t nonFinite = 0;
    for (size_t i = 0; i < image.rgb.size(); i += 3)
        nonFinite += !(std::isfinite(image.rgb[i]) && std::isfinite(image.rgb[i + 1]) && std::isfinite(image.rgb[i + 2]));
    if (nonFinite) {
        if (error)
            *error = "'" + path + "': " + std::to_string(nonFinite) + " of " + std::to_string(size_t(image.width) * image.height) +
                     " pixels are infinite or NaN; nothing was written";
        return false;
    }
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
    if (extensionOf(path) != "png") {
        if (error) *error = "'" + path + "': a display image is written as .png";
        return false;
    }
    if (width == 0 || height == 0 || rgba.size() != size_t(width) * height * 4) {
        if (error) *error = "'" + path + "': no image to write";
        return false;
    }
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
            image->rgb[3 * p + size_t(c)] = linear ? v : fromSrgb(v);
        }
    return true;
}

}  // namespace bricklight::render
