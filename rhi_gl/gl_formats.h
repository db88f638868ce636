// rhi::Format <-> GL: internal format, pixel-transfer format/type (the _INTEGER formats for integer
// textures so that values are never converted), and the per-format capability query.
#pragma once

#include "gl_functions.h"

namespace bricklight::gl::detail {

struct GlFormat {
    GLenum internalFormat = 0;  // also the image-unit format of glBindImageTexture
    GLenum pixelFormat = 0;     // glTextureSubImage / glGetTextureSubImage
    GLenum pixelType = 0;
};
const GlFormat& glFormat(rhi::Format format);

// FormatSupport bits for each format from glGetInternalformativ, with the contract's overrides.
void queryFormatSupport(const Functions& gl, uint32_t* support /* [Format::Count] */);

// Natural GL target of a texture dimension.
GLenum textureTarget(rhi::TextureDimension dimension);

// Linear [0,1] -> 8-bit sRGB code, as Vulkan converts clear colours of sRGB images.
uint8_t linearToSrgb8(float linear);

}  // namespace bricklight::gl::detail
