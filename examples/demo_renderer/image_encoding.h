// What every image writer shares, whichever library encodes the file (image_io.cpp: OpenImageIO;
// image_io_stb.cpp: stb, for builds without OpenImageIO such as Windows'): the formats a build writes, the
// display mapping of 8-bit files, and the checks before anything is written.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "path_tracer.h"

namespace bricklight::render {

// The lower-case extension of `path` without its dot ("" if none).
std::string imageExtension(const std::string& path);

// The linear-float format this build writes: "exr" with OpenImageIO, "hdr" (Radiance RGBE) with stb.
const char* floatImageExtension();
// "png" or floatImageExtension(): what writeImage accepts.
bool isWritableImageExtension(const std::string& extension);
// "(use .png or .exr)": for messages.
std::string writableImageFormats();

// Exposure, the ACES filmic curve (Narkowicz's fit) and the sRGB transfer function, as an 8-bit value.
uint8_t displayByte(float linear, float exposure);
// sRGB-encoded [0, 1] to linear.
float linearFromSrgb(float c);

// writeImage's checks before it writes: a known extension, an image of the size it says, and every pixel
// finite (a NaN would make every comparison against the file silently wrong).
bool checkImageToWrite(const std::string& path, const Image& image, std::string* error);
// writeDisplayImage's: a .png, and RGBA bytes of the size it says.
bool checkDisplayImageToWrite(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba,
                              std::string* error);

}  // namespace bricklight::render
