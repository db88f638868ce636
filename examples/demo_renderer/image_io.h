// Writing and reading images through OpenImageIO: PNG (tone-mapped, sRGB, 8 bits) and EXR (linear float).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "load_limits.h"
#include "path_tracer.h"

namespace bricklight::render {

// By extension: .png gets exposure, the ACES filmic curve (Narkowicz's fit) and the sRGB transfer
// function; .exr the linear values. False with `error` set on failure.
bool writeImage(const std::string& path, const Image& image, float exposure, std::string* error);
// A picture already mapped for display (RGBA8, sRGB-encoded, row 0 at the top: a window's display texture)
// as an 8-bit RGB .png, written as writeImage writes (a temporary file, read back, renamed).
bool writeDisplayImage(const std::string& path, uint32_t width, uint32_t height, const std::vector<uint8_t>& rgba,
                       std::string* error);
// Any format OpenImageIO reads, as linear RGB (8-bit sRGB files are linearised). An image file is untrusted
// input: a regular file only (never a FIFO or /dev/zero) of at most `limits.maxFileBytes`, and a 2D image of at
// most `limits.maxTexturePixels` pixels and 64 channels by its header, checked before anything is decoded.
bool readImage(const std::string& path, Image* image, std::string* error, const scenes::LoadLimits& limits = {});

}  // namespace bricklight::render
