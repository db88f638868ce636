// Format facts and small descriptive helpers shared by every backend and wrapper.
#include <cstring>

#include "bricklight/rhi.h"
#include "size_math.h"

namespace bricklight::rhi {

namespace {
using K = FormatInfo::Kind;
const FormatInfo kFormats[] = {
    {"Unknown", 0, 0, K::None},
    {"R8_UNORM", 1, 1, K::Unorm},
    {"R8_UINT", 1, 1, K::Uint},
    {"R16_FLOAT", 2, 1, K::Float},
    {"R16_UINT", 2, 1, K::Uint},
    {"R32_FLOAT", 4, 1, K::Float},
    {"R32_UINT", 4, 1, K::Uint},
    {"R32_SINT", 4, 1, K::Sint},
    {"RG8_UNORM", 2, 2, K::Unorm},
    {"RG16_FLOAT", 4, 2, K::Float},
    {"RG32_FLOAT", 8, 2, K::Float},
    {"RG32_UINT", 8, 2, K::Uint},
    {"RGBA8_UNORM", 4, 4, K::Unorm},
    {"RGBA8_SRGB", 4, 4, K::Srgb},
    {"RGBA16_FLOAT", 8, 4, K::Float},
    {"RGBA32_FLOAT", 16, 4, K::Float},
    {"RGBA32_UINT", 16, 4, K::Uint},
    {"R11G11B10_FLOAT", 4, 3, K::PackedFloat},
    {"RGB9E5_FLOAT", 4, 3, K::PackedFloat},
    {"D32_FLOAT", 4, 1, K::Depth},
};
static_assert(sizeof(kFormats) / sizeof(kFormats[0]) == static_cast<size_t>(Format::Count));
}  // namespace

const FormatInfo& formatInfo(Format format) {
    size_t i = static_cast<size_t>(format);
    return kFormats[i < static_cast<size_t>(Format::Count) ? i : 0];
}
const char* formatName(Format format) { return formatInfo(format).name; }
Format formatFromName(std::string_view name) {
    for (size_t i = 1; i < static_cast<size_t>(Format::Count); ++i)
        if (name == kFormats[i].name) return static_cast<Format>(i);
    return Format::Unknown;
}

const char* textureDimensionName(TextureDimension d) {
    switch (d) {
        case TextureDimension::Texture2D: return "2D";
        case TextureDimension::Texture2DArray: return "2D array";
        case TextureDimension::Texture3D: return "3D";
        case TextureDimension::TextureCube: return "cube";
    }
    return "?";
}

const char* accessName(Access a) {
    switch (a) {
        case Access::Read: return "read";
        case Access::Write: return "write";
        case Access::ReadWrite: return "read-write";
        case Access::Atomic: return "atomic";
    }
    return "?";
}

const char* bindingClassName(BindingClass c) {
    switch (c) {
        case BindingClass::Constants: return "constants";
        case BindingClass::Texture: return "textures";
        case BindingClass::ReadBuffer: return "readBuffers";
        case BindingClass::StorageBuffer: return "storageBuffers";
        case BindingClass::StorageImage: return "storageImages";
    }
    return "?";
}

uint32_t textureLayerCount(const TextureDesc& desc) {
    return (desc.dimension == TextureDimension::Texture2DArray || desc.dimension == TextureDimension::TextureCube)
               ? desc.depthOrLayers
               : 1;
}

uint32_t textureDepth(const TextureDesc& desc, uint32_t mip) {
    return desc.dimension == TextureDimension::Texture3D ? mipExtent(desc.depthOrLayers, mip) : 1;
}

uint32_t subresourceLayerCount(const TextureDesc& desc, TextureSubresource sub) {
    uint32_t layers = textureLayerCount(desc);
    if (desc.dimension == TextureDimension::Texture3D || desc.dimension == TextureDimension::Texture2D) return 1;
    if (sub.layer >= layers) return 0;
    return sub.layerCount ? sub.layerCount : layers - sub.layer;
}

uint64_t subresourceBytes(const TextureDesc& desc, TextureSubresource sub) {
    // Checked: an application may call it on a description no device has validated.
    return sizes::subresourceBytes(desc, sub).value_or(0);
}

}  // namespace bricklight::rhi
