// Translation tables between rhi enums and Vulkan.
#pragma once

#include <vulkan/vulkan.h>

#include "bricklight/rhi.h"

namespace bricklight::vulkan::detail {

VkFormat toVkFormat(rhi::Format format);
VkFormat toVkVertexFormat(rhi::VertexFormat format);
rhi::ResourceScalar vertexFormatScalar(rhi::VertexFormat format);
const char* vertexFormatName(rhi::VertexFormat format);
// The scalar type a sampler or image of this format returns in a shader.
rhi::ResourceScalar formatScalar(rhi::Format format);
bool isDepthFormat(rhi::Format format);
// Same-size reinterpretation allowed for views (colour formats of one size; depth only as itself).
bool viewFormatCompatible(rhi::Format texture, rhi::Format view);

VkCompareOp toVkCompareOp(rhi::CompareOp op);
VkFilter toVkFilter(rhi::Filter filter);
VkSamplerMipmapMode toVkMipmapMode(rhi::Filter filter);
VkSamplerAddressMode toVkAddressMode(rhi::AddressMode mode);
VkBorderColor toVkBorderColor(rhi::BorderColor color);
VkBlendFactor toVkBlendFactor(rhi::BlendFactor factor);
VkBlendOp toVkBlendOp(rhi::BlendOp op);
VkPrimitiveTopology toVkTopology(rhi::PrimitiveTopology topology);
VkCullModeFlags toVkCullMode(rhi::CullMode mode);

// FormatSupport bits from Vulkan optimal-tiling features (R11G11B10 and RGB9E5 are sampled-only by contract).
uint32_t formatSupportBits(rhi::Format format, VkFormatFeatureFlags features);

}  // namespace bricklight::vulkan::detail
