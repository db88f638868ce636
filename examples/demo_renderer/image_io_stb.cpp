// Image files through stb (Debian's libstb-dev, header-only) in builds without OpenImageIO that have it, as
// the Windows build does (OpenImageIO is not packaged for MinGW): PNG (tone-mapped, sRGB, 8 bits) and Radiance
// HDR (linear, RGBE: 8-bit mantissas with a shared exponent) are written, each decoded again before it
// replaces the target. Image files are not read (readImage, textures): decoding untrusted files needs the guarded
// reader of image_io.cpp, which this build lacks; the calls say so.
#include "image_encoding.h"
#include "image_io.h"
#include "output_file.h"
#include "texture_loader.h"

#define STB_IMAGE_WRITE_IMPLEMENTATION
#define STB_IMAGE_WRITE_STATIC
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STB_IMAGE_STATIC
#define STBI_ONLY_PNG
#define STBI_ONLY_HDR
#include <stb/stb_image.h>

namespace bricklight::render {

const char* floatImageExtension() { return "hdr"; }

namespace {

bool unavailable(const std::string& path, std::string* error) {
    if (error) *error = "'" + path + "': this build reads no image files (it writes them through stb; reading needs OpenImageIO)";
    return false;
}

// The written file decodes whole (a truncated one does not) to an image of the expected size.
bool readsBackAs(const std::string& temp, uint32_t width, uint32_t height, std::string* why) {
    int w = 0, h = 0, channels = 0;
    void* pixels = imageExtension(temp) == "hdr" ? static_cast<void*>(stbi_loadf(temp.c_str(), &w, &h, &channels, 0))
                                                 : static_cast<void*>(stbi_load(temp.c_str(), &w, &h, &channels, 0));
    if (!pixels) {
        *why = std::string("the written file does not read back: ") + stbi_failure_reason();
        return false;
    }
    stbi_image_free(pixels);
    if (uint32_t(w) != width || uint32_t(h) != height) {
        *why = "the written file reads back as " + std::to_string(w) + "x" + std::to_string(h);
        return false;
    }
    return true;
}

}  // namespace

bool writeImage(const std::string& path, const Image& image, float exposure, std::string* error) {
    if (!checkImageToWrite(path, image, error)) return false;
    const bool hdr = imageExtension(path) == "hdr";
    auto encode = [&](const std::string& temp, std::string* why) {
        const int w = int(image.width), h = int(image.height);
        int ok;
        if (hdr) {
            ok = stbi_write_hdr(temp.c_str(), w, h, 3, image.rgb.data());
        } else {
            std::vector<uint8_t> bytes(image.rgb.size());
            for (size_t i = 0; i < bytes.size(); ++i) bytes[i] = displayByte(image.rgb[i], exposure);
            ok = stbi_write_png(temp.c_str(), w, h, 3, bytes.data(), w * 3);
        }
        if (!ok) *why = "";  // stb says nothing: the caller adds errno
        return ok != 0;
    };
    return writeFileAtomically(
        path, encode, [&](const std::string& temp, std::string* why) { return readsBackAs(temp, image.width, image.height, why); },
        error);
}

bool writeDisplayImage(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba,
                       std::string* error) {
    if (!checkDisplayImageToWrite(path, width, height, rgba, error)) return false;
    auto encode = [&](const std::string& temp, std::string* why) {
        std::vector<uint8_t> rgb(size_t(width) * height * 3);
        for (size_t p = 0; p < size_t(width) * height; ++p)
            for (size_t c = 0; c < 3; ++c) rgb[3 * p + c] = rgba[4 * p + c];
        const bool ok = stbi_write_png(temp.c_str(), int(width), int(height), 3, rgb.data(), int(width) * 3) != 0;
        if (!ok) *why = "";
        return ok;
    };
    return writeFileAtomically(
        path, encode, [&](const std::string& temp, std::string* why) { return readsBackAs(temp, width, height, why); }, error);
}

bool readImage(const std::string& path, Image*, std::string* error, const scenes::LoadLimits&) { return unavailable(path, error); }

bool loadTextureLayer(const std::string& path, uint32_t, std::vector<uint8_t>*, std::string* error, const std::vector<uint8_t>*,
                      const scenes::LoadLimits&, bool) {
    return unavailable(path, error);
}

}  // namespace bricklight::render
