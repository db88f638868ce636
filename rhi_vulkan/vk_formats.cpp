#include "vk_formats.h"

namespace bricklight::vulkan::detail {

using rhi::Format;

VkFormat toVkFormat(Format f) {
    switch (f) {
        case Format::R8_UNORM: return VK_FORMAT_R8_UNORM;
        case Format::R8_UINT: return VK_FORMAT_R8_UINT;
        case Format::R16_FLOAT: return VK_FORMAT_R16_SFLOAT;
        case Format::R16_UINT: return VK_FORMAT_R16_UINT;
        case Format::R32_FLOAT: return VK_FORMAT_R32_SFLOAT;
        case Format::R32_UINT: return VK_FORMAT_R32_UINT;
        case Format::R32_SINT: return VK_FORMAT_R32_SINT;
        case Format::RG8_UNORM: return VK_FORMAT_R8G8_UNORM;
        case Format::RG16_FLOAT: return VK_FORMAT_R16G16_SFLOAT;
        case Format::RG32_FLOAT: return VK_FORMAT_R32G32_SFLOAT;
        case Format::RG32_UINT: return VK_FORMAT_R32G32_UINT;
        case Format::RGBA8_UNORM: return VK_FORMAT_R8G8B8A8_UNORM;
        case Format::RGBA8_SRGB: return VK_FORMAT_R8G8B8A8_SRGB;
        case Format::RGBA16_FLOAT: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case Format::RGBA32_FLOAT: return VK_FORMAT_R32G32B32A32_SFLOAT;
        case Format::RGBA32_UINT: return VK_FORMAT_R32G32B32A32_UINT;
        case Format::R11G11B10_FLOAT: return VK_FORMAT_B10G11R11_UFLOAT_PACK32;
        case Format::RGB9E5_FLOAT: return VK_FORMAT_E5B9G9R9_UFLOAT_PACK32;
        case Format::D32_FLOAT: return VK_FORMAT_D32_SFLOAT;
        default: return VK_FORMAT_UNDEFINED;
    }
}

VkFormat toVkVertexFormat(rhi::VertexFormat f) {
    switch (f) {
        case rhi::VertexFormat::Float1: return VK_FORMAT_R32_SFLOAT;
        case rhi::VertexFormat::Float2: return VK_FORMAT_R32G32_SFLOAT;
        case rhi::VertexFormat::Float3: return VK_FORMAT_R32G32B32_SFLOAT;
        case rhi::VertexFormat::Float4: return VK_FORMAT_R32G32B32A32_SFLOAT;
        case rhi::VertexFormat::UByte4Norm: return VK_FORMAT_R8G8B8A8_UNORM;
        case rhi::VertexFormat::UInt1: return VK_FORMAT_R32_UINT;
        case rhi::VertexFormat::Half4: return VK_FORMAT_R16G16B16A16_SFLOAT;
    }
    return VK_FORMAT_UNDEFINED;
}

rhi::ResourceScalar vertexFormatScalar(rhi::VertexFormat f) {
    return f == rhi::VertexFormat::UInt1 ? rhi::ResourceScalar::Uint : rhi::ResourceScalar::Float;
}

const char* vertexFormatName(rhi::VertexFormat f) {
    switch (f) {
        case rhi::VertexFormat::Float1: return "Float1";
        case rhi::VertexFormat::Float2: return "Float2";
        case rhi::VertexFormat::Float3: return "Float3";
        case rhi::VertexFormat::Float4: return "Float4";
        case rhi::VertexFormat::UByte4Norm: return "UByte4Norm";
        case rhi::VertexFormat::UInt1: return "UInt1";
        case rhi::VertexFormat::Half4: return "Half4";
    }
    return "?";
}

rhi::ResourceScalar formatScalar(Format f) {
    switch (rhi::formatInfo(f).kind) {
        case rhi::FormatInfo::Kind::Uint: return rhi::ResourceScalar::Uint;
        case rhi::FormatInfo::Kind::Sint: return rhi::ResourceScalar::Sint;
        case rhi::FormatInfo::Kind::None: return rhi::ResourceScalar::None;
        default: return rhi::ResourceScalar::Float;
    }
}

bool isDepthFormat(Format f) { return rhi::formatInfo(f).kind == rhi::FormatInfo::Kind::Depth; }

bool viewFormatCompatible(Format texture, Format view) {
    if (texture == view) return true;
    if (isDepthFormat(texture) || isDepthFormat(view)) return false;
    return rhi::formatInfo(texture).bytesPerTexel == rhi::formatInfo(view).bytesPerTexel;
}

VkCompareOp toVkCompareOp(rhi::CompareOp op) {
    switch (op) {
        case rhi::CompareOp::Never: return VK_COMPARE_OP_NEVER;
        case rhi::CompareOp::Less: return VK_COMPARE_OP_LESS;
        case rhi::CompareOp::Equal: return VK_COMPARE_OP_EQUAL;
        case rhi::CompareOp::LessOrEqual: return VK_COMPARE_OP_LESS_OR_EQUAL;
        case rhi::CompareOp::Greater: return VK_COMPARE_OP_GREATER;
        case rhi::CompareOp::NotEqual: return VK_COMPARE_OP_NOT_EQUAL;
        case rhi::CompareOp::GreaterOrEqual: return VK_COMPARE_OP_GREATER_OR_EQUAL;
        case rhi::CompareOp::Always: return VK_COMPARE_OP_ALWAYS;
    }
    return VK_COMPARE_OP_ALWAYS;
}

VkFilter toVkFilter(rhi::Filter f) { return f == rhi::Filter::Linear ? VK_FILTER_LINEAR : VK_FILTER_NEAREST; }
VkSamplerMipmapMode toVkMipmapMode(rhi::Filter f) {
    return f == rhi::Filter::Linear ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
}

VkSamplerAddressMode toVkAddressMode(rhi::AddressMode m) {
    switch (m) {
        case rhi::AddressMode::Repeat: return VK_SAMPLER_ADDRESS_MODE_REPEAT;
        case rhi::AddressMode::MirroredRepeat: return VK_SAMPLER_ADDRESS_MODE_MIRRORED_REPEAT;
        case rhi::AddressMode::ClampToEdge: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
        case rhi::AddressMode::ClampToBorder: return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_BORDER;
    }
    return VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
}

VkBorderColor toVkBorderColor(rhi::BorderColor c) {
    switch (c) {
        case rhi::BorderColor::TransparentBlack: return VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
        case rhi::BorderColor::OpaqueBlack: return VK_BORDER_COLOR_FLOAT_OPAQUE_BLACK;
        case rhi::BorderColor::OpaqueWhite: return VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
    }
    return VK_BORDER_COLOR_FLOAT_TRANSPARENT_BLACK;
}

VkBlendFactor toVkBlendFactor(rhi::BlendFactor f) {
    switch (f) {
        case rhi::BlendFactor::Zero: return VK_BLEND_FACTOR_ZERO;
        case rhi::BlendFactor::One: return VK_BLEND_FACTOR_ONE;
        case rhi::BlendFactor::SrcColor: return VK_BLEND_FACTOR_SRC_COLOR;
        case rhi::BlendFactor::OneMinusSrcColor: return VK_BLEND_FACTOR_ONE_MINUS_SRC_COLOR;
        case rhi::BlendFactor::DstColor: return VK_BLEND_FACTOR_DST_COLOR;
        case rhi::BlendFactor::OneMinusDstColor: return VK_BLEND_FACTOR_ONE_MINUS_DST_COLOR;
        case rhi::BlendFactor::SrcAlpha: return VK_BLEND_FACTOR_SRC_ALPHA;
        case rhi::BlendFactor::OneMinusSrcAlpha: return VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA;
        case rhi::BlendFactor::DstAlpha: return VK_BLEND_FACTOR_DST_ALPHA;
        case rhi::BlendFactor::OneMinusDstAlpha: return VK_BLEND_FACTOR_ONE_MINUS_DST_ALPHA;
    }
    return VK_BLEND_FACTOR_ONE;
}

VkBlendOp toVkBlendOp(rhi::BlendOp op) {
    switch (op) {
        case rhi::BlendOp::Add: return VK_BLEND_OP_ADD;
        case rhi::BlendOp::Subtract: return VK_BLEND_OP_SUBTRACT;
        case rhi::BlendOp::ReverseSubtract: return VK_BLEND_OP_REVERSE_SUBTRACT;
        case rhi::BlendOp::Min: return VK_BLEND_OP_MIN;
        case rhi::BlendOp::Max: return VK_BLEND_OP_MAX;
    }
    return VK_BLEND_OP_ADD;
}

VkPrimitiveTopology toVkTopology(rhi::PrimitiveTopology t) {
    switch (t) {
        case rhi::PrimitiveTopology::TriangleList: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
        case rhi::PrimitiveTopology::TriangleStrip: return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_STRIP;
        case rhi::PrimitiveTopology::LineList: return VK_PRIMITIVE_TOPOLOGY_LINE_LIST;
        case rhi::PrimitiveTopology::PointList: return VK_PRIMITIVE_TOPOLOGY_POINT_LIST;
    }
    return VK_PRIMITIVE_TOPOLOGY_TRIANGLE_LIST;
}

VkCullModeFlags toVkCullMode(rhi::CullMode m) {
    switch (m) {
        case rhi::CullMode::None: return VK_CULL_MODE_NONE;
        case rhi::CullMode::Front: return VK_CULL_MODE_FRONT_BIT;
        case rhi::CullMode::Back: return VK_CULL_MODE_BACK_BIT;
    }
    return VK_CULL_MODE_NONE;
}

uint32_t formatSupportBits(Format format, VkFormatFeatureFlags f) {
    namespace S = rhi::FormatSupport;
    uint32_t bits = 0;
    if (f & VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT) bits |= S::Sampled;
    if (f & VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT) bits |= S::Filterable;
    if (f & VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT) bits |= S::Storage;
    if (f & VK_FORMAT_FEATURE_STORAGE_IMAGE_ATOMIC_BIT) bits |= S::StorageAtomic;
    if (f & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT) bits |= S::RenderTarget;
    if (f & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BLEND_BIT) bits |= S::Blendable;
    if (f & VK_FORMAT_FEATURE_DEPTH_STENCIL_ATTACHMENT_BIT) bits |= S::DepthTarget;
    // Every texture is created with TRANSFER_SRC|DST; a format without them is unusable here.
    const VkFormatFeatureFlags transfer = VK_FORMAT_FEATURE_TRANSFER_SRC_BIT | VK_FORMAT_FEATURE_TRANSFER_DST_BIT;
    if ((f & transfer) != transfer) bits = 0;
    if (format == Format::R11G11B10_FLOAT || format == Format::RGB9E5_FLOAT) bits &= ~(S::Storage | S::StorageAtomic);
    return bits;
}

}  // namespace bricklight::vulkan::detail
