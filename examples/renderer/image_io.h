// Writing and reading images through OpenImageIO: PNG (tone-mapped, sRGB, 8 bits) and EXR (linear float).
#pragma once

#include <string>

#include "path_tracer.h"

namespace bricklight::render {

// By extension: .png gets exposure, the ACES filmic curve (Narkowicz's fit) and the sRGB transfer
// function; .exr the linear values. False with `error` set on failure.
bool writeImage(const std::string& path, const Image& image, float exposure, std::string* error);
// Any format OpenImageIO reads, as linear RGB (8-bit sRGB files are linearised).
bool readImage(const std::string& path, Image* image, std::string* error);

}  // namespace bricklight::render
