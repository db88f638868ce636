// Base-colour textures for the renderer: any image OpenImageIO reads, resampled to a square layer of
// RGBA8 sRGB texels (rows top to bottom). Texture files come with model files from anywhere: a file must
// be a regular file within LoadLimits::maxFileBytes, and its header is read before any pixel is decoded
// (an image over LoadLimits::maxTexturePixels is refused without allocating for it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "load_limits.h"

namespace bricklight::render {

// Appends size * size * 4 bytes to `texels`; false with `error` ("'path' cannot be loaded: why") if the
// file cannot be read or is over `limits`. With `encoded` (a texture embedded in a model file), decodes
// those bytes instead; `path` names it. With `coverage` (an opacity map, TriangleMesh::alphaTexture), an image
// without an alpha channel gives its first channel as the alpha.
bool loadTextureLayer(const std::string& path, uint32_t size, std::vector<uint8_t>* texels, std::string* error,
                      const std::vector<uint8_t>* encoded = nullptr, const scenes::LoadLimits& limits = {}, bool coverage = false);

}  // namespace bricklight::render
