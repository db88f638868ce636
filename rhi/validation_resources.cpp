// Validation of resource descriptions and transfer ranges against the device's capabilities.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "size_math.h"
#include "validation_internal.h"

namespace bricklight::rhi::validation {

std::string quoted(const std::string& s) { return "'" + s + "'"; }

std::string describeTexture(const ObjectTable& t, TextureHandle h) {
    auto it = t.textures.find(h.id);
    if (it != t.textures.end() && !it->second.debugName.empty()) return "texture " + quoted(it->second.debugName);
    return "texture #" + std::to_string(h.id);
}

std::string describeBuffer(const ObjectTable& t, BufferHandle h) {
    auto it = t.buffers.find(h.id);
    if (it != t.buffers.end() && !it->second.debugName.empty()) return "buffer " + quoted(it->second.debugName);
    return "buffer #" + std::to_string(h.id);
}

namespace {
constexpr uint32_t kKnownTextureUsage = TextureUsage::Sampled | TextureUsage::Storage | TextureUsage::RenderTarget | TextureUsage::DepthTarget;
constexpr uint32_t kKnownBufferUsage =
    BufferUsage::ShaderRead | BufferUsage::ShaderWrite | BufferUsage::IndirectArgs | BufferUsage::Vertex | BufferUsage::Index;

std::string hex(uint32_t bits) {
    char text[16];
    std::snprintf(text, sizeof text, "0x%x", bits);
    return text;
}

template <typename Map, typename Dead>
const typename Map::mapped_type* live(const Map& map, const Dead& dead, uint32_t id, const char* kind,
                                      const std::string& field, Report& r) {
    if (id == 0) {
        r.error(field + ": null " + kind + " handle");
        return nullptr;
    }
    auto it = map.find(id);
    if (it != map.end()) return &it->second;
    auto d = dead.find(id);
    if (d != dead.end())
        r.error(field + ": " + kind + " " + quoted(d->second) + " (#" + std::to_string(id) +
                ") was destroyed and may not be used");
    else
        r.error(field + ": unknown " + kind + " handle #" + std::to_string(id));
    return nullptr;
}
}  // namespace

const TextureDesc* liveTexture(const ObjectTable& t, TextureHandle h, const std::string& field, Report& r) {
    return live(t.textures, t.destroyedTextures, h.id, "texture", field, r);
}
const BufferDesc* liveBuffer(const ObjectTable& t, BufferHandle h, const std::string& field, Report& r) {
    return live(t.buffers, t.destroyedBuffers, h.id, "buffer", field, r);
}
const SamplerDesc* liveSampler(const ObjectTable& t, SamplerHandle h, const std::string& field, Report& r) {
    return live(t.samplers, t.destroyedSamplers, h.id, "sampler", field, r);
}
const ShaderInfo* liveShader(const ObjectTable& t, ShaderHandle h, const std::string& field, Report& r) {
    return live(t.shaders, t.destroyedShaders, h.id, "shader", field, r);
}

void checkTextureDesc(const TextureDesc& d, const Capabilities& caps, Report& r) {
    if (d.format == Format::Unknown || d.format >= Format::Count) {
        r.error("format: Unknown is not a texture format");
        return;
    }
    if (d.width == 0 || d.height == 0 || d.depthOrLayers == 0) {
        r.error("zero-size texture (" + std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
                std::to_string(d.depthOrLayers) + "): width, height and depthOrLayers must be at least 1");
        return;
    }
    const Limits& l = caps.limits;
    switch (d.dimension) {
        case TextureDimension::Texture2D:
            if (d.depthOrLayers != 1) r.error("depthOrLayers must be 1 for a 2D texture (use Texture2DArray)");
            [[fallthrough]];
        case TextureDimension::Texture2DArray:
            if (d.width > l.maxTextureSize2D || d.height > l.maxTextureSize2D)
                r.error("size " + std::to_string(d.width) + "x" + std::to_string(d.height) +
                        " exceeds maxTextureSize2D " + std::to_string(l.maxTextureSize2D));
            if (d.depthOrLayers > l.maxTextureArrayLayers)
                r.error("depthOrLayers " + std::to_string(d.depthOrLayers) + " exceeds maxTextureArrayLayers " +
                        std::to_string(l.maxTextureArrayLayers));
            break;
        case TextureDimension::Texture3D:
            if (std::max({d.width, d.height, d.depthOrLayers}) > l.maxTextureSize3D)
                r.error("size exceeds maxTextureSize3D " + std::to_string(l.maxTextureSize3D));
            break;
        case TextureDimension::TextureCube:
            if (d.width != d.height) r.error("cube faces must be square");
            if (d.depthOrLayers != 6) r.error("a cube texture has depthOrLayers 6");
            break;
        default:
            r.error("dimension " + std::to_string(int(d.dimension)) + " is not a TextureDimension");
            return;
    }
    // Counted without shifting: `while (largest >> n) ++n` shifted by 32 for a width of 2^31 or more, which
    // x86 takes as a shift by 0, and looped forever.
    const uint32_t maxMips = sizes::fullMipCount(sizes::largestExtent(d));
    if (d.mipLevels == 0 || d.mipLevels > maxMips)
        r.error("mipLevels " + std::to_string(d.mipLevels) + " out of range 1.." + std::to_string(maxMips));
    if (d.usage == 0) r.error("usage is empty: give at least one TextureUsage bit");
    if (const uint32_t unknown = d.usage & ~kKnownTextureUsage) r.error("usage has unknown bits " + hex(unknown) + " (TextureUsage has 4)");
    const char* fmt = formatName(d.format);
    auto need = [&](uint32_t usageBit, uint32_t supportBit, const char* usageName) {
        if ((d.usage & usageBit) && !caps.supports(d.format, supportBit))
            r.error(std::string("format ") + fmt + " does not support " + usageName + " on this device");
    };
    need(TextureUsage::Sampled, FormatSupport::Sampled, "Sampled");
    need(TextureUsage::Storage, FormatSupport::Storage, "Storage");
    need(TextureUsage::RenderTarget, FormatSupport::RenderTarget, "RenderTarget");
    need(TextureUsage::DepthTarget, FormatSupport::DepthTarget, "DepthTarget");
    if ((d.usage & TextureUsage::DepthTarget) && d.dimension == TextureDimension::Texture3D)
        r.error("a 3D texture cannot be a depth target");
}

void checkBufferDesc(const BufferDesc& d, Report& r) {
    if (d.size == 0) r.error("zero-size buffer: size must be at least 1 byte");
    if (d.usage == 0) r.error("usage is empty: give at least one BufferUsage bit");
    if (const uint32_t unknown = d.usage & ~kKnownBufferUsage) r.error("usage has unknown bits " + hex(unknown) + " (BufferUsage has 5)");
    if (d.structStride) {
        if (d.structStride % 4) r.error("structStride " + std::to_string(d.structStride) + " is not a multiple of 4");
        else if (d.size % d.structStride)
            r.error("size " + std::to_string(d.size) + " is not a multiple of structStride " +
                    std::to_string(d.structStride));
    }
    if ((d.usage & (BufferUsage::ShaderRead | BufferUsage::ShaderWrite | BufferUsage::IndirectArgs)) && d.size % 4)
        r.error("size " + std::to_string(d.size) + " of a shader/indirect buffer is not a multiple of 4");
}

void checkSamplerDesc(const SamplerDesc& d, Report& r) {
    auto inRange = [&](auto value, int count, const char* field) {
        if (int(value) >= count) r.error(std::string(field) + " " + std::to_string(int(value)) + " is out of range");
    };
    inRange(d.minFilter, 2, "minFilter"), inRange(d.magFilter, 2, "magFilter"), inRange(d.mipFilter, 2, "mipFilter");
    inRange(d.addressU, 4, "addressU"), inRange(d.addressV, 4, "addressV"), inRange(d.addressW, 4, "addressW");
    inRange(d.borderColor, 3, "borderColor"), inRange(d.compareOp, 8, "compareOp");
    if (!(d.maxAnisotropy >= 1.0f && d.maxAnisotropy <= 16.0f)) r.error("maxAnisotropy must be in [1, 16]");
    if (!(d.minLod <= d.maxLod)) r.error("minLod must not exceed maxLod");
    if (!std::isfinite(d.mipLodBias)) r.error("mipLodBias is not finite");
}

void checkShaderDesc(const ShaderDesc& d, const Capabilities& caps, Report& r) {
    if (!d.blob) {
        r.error("null shader: ShaderDesc::blob is null (findShader returned no shader?)");
        return;
    }
    if (!d.blob->spirv || !d.blob->glsl) r.error("shader blob has no code");
    if (d.blob->stage == ShaderStage::Geometry && !caps.geometryShader)
        r.error("geometry shaders are not supported on this device");
    if (d.blob->stage == ShaderStage::Compute) {
        const uint32_t* s = d.blob->reflection.localSize;
        const Limits& l = caps.limits;
        for (int i = 0; i < 3; ++i)
            if (s[i] > l.maxComputeGroupSize[i])
                r.error("local size " + std::to_string(s[i]) + " in dimension " + std::to_string(i) +
                        " exceeds maxComputeGroupSize " + std::to_string(l.maxComputeGroupSize[i]));
        if (uint64_t(s[0]) * s[1] * s[2] > l.maxComputeGroupInvocations)
            r.error("local size exceeds maxComputeGroupInvocations " + std::to_string(l.maxComputeGroupInvocations));
    }
}

bool checkSubresource(const TextureDesc& d, TextureSubresource sub, const std::string& field, Report& r) {
    if (sub.mip >= d.mipLevels) {
        r.error(field + ": mip " + std::to_string(sub.mip) + " out of range (texture " + quoted(d.debugName) +
                " has " + std::to_string(d.mipLevels) + ")");
        return false;
    }
    uint32_t layers = textureLayerCount(d);
    if (sub.layer >= layers || (sub.layerCount && sub.layerCount > layers - sub.layer)) {
        r.error(field + ": layers " + std::to_string(sub.layer) + "+" + std::to_string(sub.layerCount) +
                " out of range (texture " + quoted(d.debugName) + " has " + std::to_string(layers) + ")");
        return false;
    }
    return true;
}

bool checkBufferRange(const BufferDesc& d, uint64_t offset, uint64_t size, const std::string& field, Report& r) {
    if (!sizes::rangeInside(offset, size, d.size)) {
        r.error(field + ": range [" + std::to_string(offset) + ", +" + std::to_string(size) +
                ") exceeds buffer " + quoted(d.debugName) + " of " + std::to_string(d.size) + " bytes");
        return false;
    }
    return true;
}

}  // namespace bricklight::rhi::validation
