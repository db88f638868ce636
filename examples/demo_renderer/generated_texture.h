// Generated textures (scenes::GeneratedTexture: procedural texels of the built-in scenes) as texture-array
// layers, without an image library: the renderer's textures work the same in builds without OpenImageIO.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "scene_geometry.h"

namespace bricklight::render {

// Appends size * size * 4 bytes to `texels`: the texture resampled (bilinear, edges clamped; a copy when it is
// already size x size), each channel as stored (sRGB colour, linear alpha, as the file loader keeps them). False
// with `error` naming the texture when its size is 0, over 16384 a side, or its byte count does not match it.
bool generatedTextureLayer(const scenes::GeneratedTexture& texture, uint32_t size, std::vector<uint8_t>* texels, std::string* error);

}  // namespace bricklight::render
