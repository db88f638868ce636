// Writing and reading images through OpenImageIO: PNG (tone-mapped, sRGB, 8 bits) and EXR (linear float).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "path_tracer.h"

namespace bricklight::render {

// By extension: .png gets exposure, the ACES filmic curve (Narkowicz's fit) and the sRGB transfer
// function; .exr the linear values. False with `error` set on failure.
bool writeImage(const std::string& path, const Image& image, float exposure, std::string* error);
// A picture already mapped for display (RGBA8, sRGB-encoded, row 0 at the top: a window's display texture)
// as an 8-bit RGB .png, written as writeImage writes (a temporary file, read back, renamed).
bool writeDisplayImage(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba,
                       std::string* error);
// Any format OpenImageIO reads, as linear RGB (8-bit sRGB files are linearised).
bool readImage(const std::string& path, Image* image, std::string* error);

}  // namespace bricklight::render
