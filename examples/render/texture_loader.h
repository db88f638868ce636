// Base-colour textures for the renderer: any image OpenImageIO reads, resampled to a square layer of
// RGBA8 sRGB texels (rows top to bottom).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace bricklight::render {

// Appends size * size * 4 bytes to `texels`; false with `error` ("'path': why") if the file cannot be read.
// With `encoded` (a texture embedded in a model file), decodes those bytes instead; `path` names it.
bool loadTextureLayer(const std::string& path, uint32_t size, std::vector<uint8_t>* texels, std::string* error,
                      const std::vector<uint8_t>* encoded = nullptr);

}  // namespace bricklight::render
