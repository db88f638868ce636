#include "image_encoding.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace bricklight::render {

namespace {

float filmic(float x) {  // ACES approximation (K. Narkowicz 2015), input already exposed
    x = std::max(0.0f, x);
    return std::clamp((x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

float toSrgb(float c) { return c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

}  // namespace

std::string imageExtension(const std::string& path) {
    const size_t dot = path.find_last_of('.');
    std::string ext = dot == std::string::npos ? "" : path.substr(dot + 1);
    for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

bool isWritableImageExtension(const std::string& extension) {
    return extension == "png" || extension == floatImageExtension();
}

std::string writableImageFormats() { return std::string("(use .png or .") + floatImageExtension() + ")"; }

uint8_t displayByte(float linear, float exposure) { return uint8_t(std::lround(toSrgb(filmic(linear * exposure)) * 255.0f)); }

float linearFromSrgb(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }

bool checkImageToWrite(const std::string& path, const Image& image, std::string* error) {
    if (!isWritableImageExtension(imageExtension(path))) {
        if (error) *error = "'" + path + "': unsupported output format " + writableImageFormats();
        return false;
    }
    if (image.width == 0 || image.height == 0 || image.rgb.size() != size_t(image.width) * image.height * 3) {
        if (error) *error = "'" + path + "': no image to write";
        return false;
    }
    size_t nonFinite = 0;
    for (size_t i = 0; i < image.rgb.size(); i += 3)
        nonFinite += !(std::isfinite(image.rgb[i]) && std::isfinite(image.rgb[i + 1]) && std::isfinite(image.rgb[i + 2]));
    if (nonFinite) {
        if (error)
            *error = "'" + path + "': " + std::to_string(nonFinite) + " of " + std::to_string(size_t(image.width) * image.height) +
                     " pixels are infinite or NaN; nothing was written";
        return false;
    }
    return true;
}

bool checkDisplayImageToWrite(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba,
                              std::string* error) {
    if (imageExtension(path) != "png") {
        if (error) *error = "'" + path + "': a display image is written as .png";
        return false;
    }
    if (width == 0 || height == 0 || rgba.size() != size_t(width) * height * 4) {
        if (error) *error = "'" + path + "': no image to write";
        return false;
    }
    return true;
}

}  // namespace bricklight::render
