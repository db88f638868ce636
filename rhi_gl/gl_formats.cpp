#include "gl_formats.h"

#include <cmath>

namespace bricklight::gl::detail {

using rhi::Format;

const GlFormat& glFormat(Format format) {
    static const GlFormat kTable[] = {
        {0, 0, 0},                                                          // Unknown
        {GL_R8, GL_RED, GL_UNSIGNED_BYTE},                                  // R8_UNORM
        {GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE},                        // R8_UINT
        {GL_R16F, GL_RED, GL_HALF_FLOAT},                                   // R16_FLOAT
        {GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT},                      // R16_UINT
        {GL_R32F, GL_RED, GL_FLOAT},                                        // R32_FLOAT
        {GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT},                        // R32_UINT
        {GL_R32I, GL_RED_INTEGER, GL_INT},                                  // R32_SINT
        {GL_RG8, GL_RG, GL_UNSIGNED_BYTE},                                  // RG8_UNORM
        {GL_RG16F, GL_RG, GL_HALF_FLOAT},                                   // RG16_FLOAT
        {GL_RG32F, GL_RG, GL_FLOAT},                                        // RG32_FLOAT
        {GL_RG32UI, GL_RG_INTEGER, GL_UNSIGNED_INT},                        // RG32_UINT
        {GL_RGBA8, GL_RGBA, GL_UNSIGNED_BYTE},                              // RGBA8_UNORM
        {GL_SRGB8_ALPHA8, GL_RGBA, GL_UNSIGNED_BYTE},                       // RGBA8_SRGB (bytes as stored)
        {GL_RGBA16F, GL_RGBA, GL_HALF_FLOAT},                               // RGBA16_FLOAT
        {GL_RGBA32F, GL_RGBA, GL_FLOAT},                                    // RGBA32_FLOAT
        {GL_RGBA32UI, GL_RGBA_INTEGER, GL_UNSIGNED_INT},                    // RGBA32_UINT
        {GL_R11F_G11F_B10F, GL_RGB, GL_UNSIGNED_INT_10F_11F_11F_REV},       // R11G11B10_FLOAT (= Vulkan B10G11R11)
        {GL_RGB9_E5, GL_RGB, GL_UNSIGNED_INT_5_9_9_9_REV},                  // RGB9E5_FLOAT (= Vulkan E5B9G9R9)
        {GL_DEPTH_COMPONENT32F, GL_DEPTH_COMPONENT, GL_FLOAT},              // D32_FLOAT
    };
    static_assert(sizeof(kTable) / sizeof(kTable[0]) == static_cast<size_t>(Format::Count));
    size_t i = static_cast<size_t>(format);
    return kTable[i < static_cast<size_t>(Format::Count) ? i : 0];
}

GLenum textureTarget(rhi::TextureDimension dimension) {
    switch (dimension) {
        case rhi::TextureDimension::Texture2D: return GL_TEXTURE_2D;
        case rhi::TextureDimension::Texture2DArray: return GL_TEXTURE_2D_ARRAY;
        case rhi::TextureDimension::Texture3D: return GL_TEXTURE_3D;
        case rhi::TextureDimension::TextureCube: return GL_TEXTURE_CUBE_MAP;
    }
    return GL_TEXTURE_2D;
}

void queryFormatSupport(const Functions& gl, uint32_t* support) {
    namespace FS = rhi::FormatSupport;
    auto query = [&](GLenum internalFormat, GLenum pname) {
        GLint value = 0;
        gl.GetInternalformativ(GL_TEXTURE_2D, internalFormat, pname, 1, &value);
        return value;
    };
    auto yes = [](GLint v) { return v == GL_FULL_SUPPORT || v == GL_CAVEAT_SUPPORT || v == GL_TRUE; };
    for (size_t i = 1; i < static_cast<size_t>(Format::Count); ++i) {
        const Format format = static_cast<Format>(i);
        const GLenum ifmt = glFormat(format).internalFormat;
        const auto kind = rhi::formatInfo(format).kind;
        uint32_t bits = 0;
        if (query(ifmt, GL_INTERNALFORMAT_SUPPORTED) != GL_TRUE) {
            support[i] = 0;
            continue;
        }
        bits |= FS::Sampled;
        if (yes(query(ifmt, GL_FILTER))) bits |= FS::Filterable;
        if (kind == rhi::FormatInfo::Kind::Depth) {
            if (yes(query(ifmt, GL_DEPTH_RENDERABLE))) bits |= FS::DepthTarget;
        } else {
            if (yes(query(ifmt, GL_FRAMEBUFFER_RENDERABLE))) bits |= FS::RenderTarget;
            if (yes(query(ifmt, GL_FRAMEBUFFER_BLEND))) bits |= FS::Blendable;
            // Contract: sRGB and the packed floats are never storage, whatever the driver says (Vulkan parity).
            const bool storageAllowed = format != Format::RGBA8_SRGB && format != Format::R11G11B10_FLOAT && format != Format::RGB9E5_FLOAT;
            if (storageAllowed && yes(query(ifmt, GL_SHADER_IMAGE_LOAD)) && yes(query(ifmt, GL_SHADER_IMAGE_STORE)))
                bits |= FS::Storage;
            // GLSL image atomics exist only for r32ui / r32i: the driver's answer is ANDed with that (the spec
            // says GL_TRUE, Mesa answers GL_FULL_SUPPORT: both count).
            const bool atomicFormat = format == Format::R32_UINT || format == Format::R32_SINT;
            if ((bits & FS::Storage) && atomicFormat && yes(query(ifmt, GL_SHADER_IMAGE_ATOMIC)))
                bits |= FS::StorageAtomic;
        }
        // Integer formats are never filterable or blendable, whatever a driver reports.
        if (kind == rhi::FormatInfo::Kind::Uint || kind == rhi::FormatInfo::Kind::Sint)
            bits &= ~(FS::Filterable | FS::Blendable);
        support[i] = bits;
    }
}

uint8_t linearToSrgb8(float linear) {
    float c = std::isnan(linear) ? 0.0f : std::fmin(std::fmax(linear, 0.0f), 1.0f);
    float s = c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return static_cast<uint8_t>(std::lround(s * 255.0f));
}

}  // namespace bricklight::gl::detail
