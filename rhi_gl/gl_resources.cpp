// Creation, wrapping and destruction of textures, buffers, samplers and shaders.
#include <algorithm>
#include <cmath>

#include "../rhi/size_math.h"
#include "gl_device.h"
#include "gl_formats.h"

namespace bricklight::gl::detail {

using namespace rhi;

namespace {
uint32_t maxMipLevels(const TextureDesc& d) { return sizes::fullMipCount(sizes::largestExtent(d)); }
}  // namespace

bool Device::checkTextureDesc(const Call& call, const TextureDesc& d) const {
    if (d.format == Format::Unknown || d.format >= Format::Count) return fail(call, "format: not a texture format");
    if (d.width == 0 || d.height == 0 || d.depthOrLayers == 0)
        return fail(call, "zero-size texture (" + std::to_string(d.width) + "x" + std::to_string(d.height) + "x" +
                              std::to_string(d.depthOrLayers) + ")");
    const Limits& l = caps_.limits;
    switch (d.dimension) {
        case TextureDimension::Texture2D:
        case TextureDimension::Texture2DArray:
        case TextureDimension::TextureCube:
            if (d.dimension == TextureDimension::Texture2D && d.depthOrLayers != 1)
                return fail(call, "depthOrLayers must be 1 for a 2D texture (use Texture2DArray)");
            if (d.width > l.maxTextureSize2D || d.height > l.maxTextureSize2D)
                return fail(call, "size exceeds maxTextureSize2D " + std::to_string(l.maxTextureSize2D));
            if (d.depthOrLayers > l.maxTextureArrayLayers)
                return fail(call, "depthOrLayers exceeds maxTextureArrayLayers " + std::to_string(l.maxTextureArrayLayers));
            if (d.dimension == TextureDimension::TextureCube && (d.width != d.height || d.depthOrLayers != 6))
                return fail(call, "a cube texture has square faces and depthOrLayers 6");
            break;
        case TextureDimension::Texture3D:
            if (std::max({d.width, d.height, d.depthOrLayers}) > l.maxTextureSize3D)
                return fail(call, "size exceeds maxTextureSize3D " + std::to_string(l.maxTextureSize3D));
            break;
        default: return fail(call, "dimension: not a texture dimension");
    }
    if (d.mipLevels < 1 || d.mipLevels > maxMipLevels(d))
        return fail(call, "mipLevels " + std::to_string(d.mipLevels) + " out of range 1.." + std::to_string(maxMipLevels(d)));
    if (d.usage == 0) return fail(call, "usage is empty: give at least one TextureUsage bit");
    // Within the limits above the count fits 64 bits; a texture larger than the memory there is is refused here
    // rather than by a driver that may try to allocate it.
    const auto bytes = sizes::textureBytes(d);
    if (!bytes || *bytes > maxResourceBytes_)
        return fail(call, "size " + (bytes ? std::to_string(*bytes) + " bytes" : std::string("beyond 2^64 bytes")) +
                              " exceeds the largest resource this device can hold (" + std::to_string(maxResourceBytes_) + " bytes)");
    const struct {
        uint32_t usage, support;
        const char* name;
    } needs[] = {{TextureUsage::Sampled, FormatSupport::Sampled, "sampling"},
                 {TextureUsage::Storage, FormatSupport::Storage, "storage"},
                 {TextureUsage::RenderTarget, FormatSupport::RenderTarget, "render target"},
                 {TextureUsage::DepthTarget, FormatSupport::DepthTarget, "depth target"}};
    for (const auto& n : needs)
        if ((d.usage & n.usage) && !caps_.supports(d.format, n.support))
            return fail(call, std::string("format ") + formatName(d.format) + " does not support " + n.name + " on this device");
    if (d.dimension == TextureDimension::Texture3D && (d.usage & TextureUsage::DepthTarget))
        return fail(call, "a 3D texture cannot be a depth target");
    return true;
}

bool Device::uploadTexture(const TextureRecord& t, uint32_t mip, uint32_t layer, uint32_t layers, const void* data) {
    const GlFormat& f = glFormat(t.desc.format);
    const GLsizei w = GLsizei(mipExtent(t.desc.width, mip)), h = GLsizei(mipExtent(t.desc.height, mip));
    switch (t.desc.dimension) {
        case TextureDimension::Texture2D:
            gl.TextureSubImage2D(t.name, GLint(mip), 0, 0, w, h, f.pixelFormat, f.pixelType, data);
            break;
        case TextureDimension::Texture3D:
            gl.TextureSubImage3D(t.name, GLint(mip), 0, 0, 0, w, h, GLsizei(textureDepth(t.desc, mip)), f.pixelFormat,
                                 f.pixelType, data);
            break;
        default:  // arrays and cubes (DSA treats a cube map as 6 layers)
            gl.TextureSubImage3D(t.name, GLint(mip), 0, 0, GLint(layer), w, h, GLsizei(layers), f.pixelFormat,
                                 f.pixelType, data);
            break;
    }
    return true;
}

TextureHandle Device::createTexture(const TextureDesc& desc, const void* initialData) {
    makeCurrent();
    Call call{"createTexture", desc.debugName.c_str()};
    if (!checkTextureDesc(call, desc)) return {};
    TextureRecord t;
    t.desc = desc;
    t.target = textureTarget(desc.dimension);
    drainErrors(gl);
    gl.CreateTextures(t.target, 1, &t.name);
    const GLenum ifmt = glFormat(desc.format).internalFormat;
    if (desc.dimension == TextureDimension::Texture2D || desc.dimension == TextureDimension::TextureCube)
        gl.TextureStorage2D(t.name, GLsizei(desc.mipLevels), ifmt, GLsizei(desc.width), GLsizei(desc.height));
    else
        gl.TextureStorage3D(t.name, GLsizei(desc.mipLevels), ifmt, GLsizei(desc.width), GLsizei(desc.height),
                            GLsizei(desc.depthOrLayers));
    if (GLenum err = gl.GetError(); err != GL_NO_ERROR) {
        gl.DeleteTextures(1, &t.name);
        fail(call, "glTextureStorage failed (GL error " + hex(err) + (err == GL_OUT_OF_MEMORY ? ", out of memory)" : ")"));
        return {};
    }
    t.id = newId();
    if (!desc.debugName.empty()) gl.ObjectLabel(GL_TEXTURE, t.name, -1, desc.debugName.c_str());
    if (initialData) {
        // All mips of layer 0, then all mips of layer 1...; a 3D mip holds all its slices.
        setPixelStore();
        const auto* bytes = static_cast<const unsigned char*>(initialData);
        for (uint32_t layer = 0; layer < textureLayerCount(desc); ++layer)
            for (uint32_t mip = 0; mip < desc.mipLevels; ++mip) {
                uploadTexture(t, mip, layer, 1, bytes);
                bytes += subresourceBytes(desc, TextureSubresource{mip, layer, 1});
            }
    }
    TextureHandle handle{t.id};
    textures_.emplace(t.id, std::move(t));
    return handle;
}

bool Device::checkBufferDesc(const Call& call, const BufferDesc& d) const {
    if (d.size == 0) return fail(call, "zero-size buffer: size must be at least 1 byte");
    if (d.size > maxResourceBytes_)
        return fail(call, "size " + std::to_string(d.size) + " exceeds the largest buffer this device can hold (" +
                              std::to_string(maxResourceBytes_) + " bytes)");
    if (d.usage == 0) return fail(call, "usage is empty: give at least one BufferUsage bit");
    if (d.structStride && d.structStride % 4)
        return fail(call, "structStride " + std::to_string(d.structStride) + " is not a multiple of 4");
    if (d.structStride && d.size % d.structStride)
        return fail(call, "size " + std::to_string(d.size) + " is not a multiple of structStride " + std::to_string(d.structStride));
    const uint32_t wordUsages = BufferUsage::ShaderRead | BufferUsage::ShaderWrite | BufferUsage::IndirectArgs;
    if ((d.usage & wordUsages) && d.size % 4)
        return fail(call, "size " + std::to_string(d.size) + " of a shader/indirect buffer is not a multiple of 4");
    return true;
}

BufferHandle Device::createBuffer(const BufferDesc& desc, const void* initialData) {
    makeCurrent();
    Call call{"createBuffer", desc.debugName.c_str()};
    if (!checkBufferDesc(call, desc)) return {};
    BufferRecord b;
    b.desc = desc;
    drainErrors(gl);
    gl.CreateBuffers(1, &b.name);
    gl.NamedBufferStorage(b.name, GLsizeiptr(desc.size), initialData, GL_DYNAMIC_STORAGE_BIT);
    if (GLenum err = gl.GetError(); err != GL_NO_ERROR) {
        gl.DeleteBuffers(1, &b.name);
        fail(call, "glNamedBufferStorage failed (GL error " + hex(err) + (err == GL_OUT_OF_MEMORY ? ", out of memory)" : ")"));
        return {};
    }
    // New buffers read as zero on every backend (GL leaves them undefined; NVIDIA's hold old data).
    if (!initialData) gl.ClearNamedBufferSubData(b.name, GL_R8, 0, GLsizeiptr(desc.size), GL_RED, GL_UNSIGNED_BYTE, nullptr);
    b.id = newId();
    if (!desc.debugName.empty()) gl.ObjectLabel(GL_BUFFER, b.name, -1, desc.debugName.c_str());
    BufferHandle handle{b.id};
    buffers_.emplace(b.id, std::move(b));
    return handle;
}

namespace {
GLenum wrapMode(AddressMode m) {
    switch (m) {
        case AddressMode::Repeat: return GL_REPEAT;
        case AddressMode::MirroredRepeat: return GL_MIRRORED_REPEAT;
        case AddressMode::ClampToEdge: return GL_CLAMP_TO_EDGE;
        case AddressMode::ClampToBorder: return GL_CLAMP_TO_BORDER;
    }
    return GL_CLAMP_TO_EDGE;
}
GLenum minFilter(Filter min, Filter mip) {
    if (min == Filter::Nearest) return mip == Filter::Nearest ? GL_NEAREST_MIPMAP_NEAREST : GL_NEAREST_MIPMAP_LINEAR;
    return mip == Filter::Nearest ? GL_LINEAR_MIPMAP_NEAREST : GL_LINEAR_MIPMAP_LINEAR;
}
}  // namespace

SamplerHandle Device::createSampler(const SamplerDesc& d) {
    makeCurrent();
    Call call{"createSampler", d.debugName.c_str()};
    if (!(d.maxAnisotropy >= 1.0f && d.maxAnisotropy <= 16.0f)) return fail(call, "maxAnisotropy must be in [1, 16]"), SamplerHandle{};
    if (!(d.minLod <= d.maxLod)) return fail(call, "minLod must not exceed maxLod"), SamplerHandle{};
    if (!std::isfinite(d.mipLodBias)) return fail(call, "mipLodBias is not finite"), SamplerHandle{};
    SamplerRecord s;
    s.desc = d;
    gl.CreateSamplers(1, &s.name);
    gl.SamplerParameteri(s.name, GL_TEXTURE_MIN_FILTER, GLint(minFilter(d.minFilter, d.mipFilter)));
    gl.SamplerParameteri(s.name, GL_TEXTURE_MAG_FILTER, d.magFilter == Filter::Nearest ? GL_NEAREST : GL_LINEAR);
    gl.SamplerParameteri(s.name, GL_TEXTURE_WRAP_S, GLint(wrapMode(d.addressU)));
    gl.SamplerParameteri(s.name, GL_TEXTURE_WRAP_T, GLint(wrapMode(d.addressV)));
    gl.SamplerParameteri(s.name, GL_TEXTURE_WRAP_R, GLint(wrapMode(d.addressW)));
    const float borders[3][4] = {{0, 0, 0, 0}, {0, 0, 0, 1}, {1, 1, 1, 1}};
    gl.SamplerParameterfv(s.name, GL_TEXTURE_BORDER_COLOR, borders[size_t(d.borderColor) % 3]);
    gl.SamplerParameterf(s.name, GL_TEXTURE_MIN_LOD, d.minLod);
    gl.SamplerParameterf(s.name, GL_TEXTURE_MAX_LOD, d.maxLod);
    gl.SamplerParameterf(s.name, GL_TEXTURE_LOD_BIAS, d.mipLodBias);
    if (anisotropy_) gl.SamplerParameterf(s.name, GL_TEXTURE_MAX_ANISOTROPY, std::min(d.maxAnisotropy, maxAnisotropy_));
    gl.SamplerParameteri(s.name, GL_TEXTURE_COMPARE_MODE, d.compareEnable ? GL_COMPARE_REF_TO_TEXTURE : GL_NONE);
    gl.SamplerParameteri(s.name, GL_TEXTURE_COMPARE_FUNC, GLint(compareFunc(d.compareOp)));
    s.id = newId();
    if (!d.debugName.empty()) gl.ObjectLabel(GL_SAMPLER, s.name, -1, d.debugName.c_str());
    SamplerHandle handle{s.id};
    samplers_.emplace(s.id, std::move(s));
    return handle;
}

ShaderHandle Device::createShader(const ShaderDesc& desc) {
    makeCurrent();
    std::string name = !desc.debugName.empty() ? desc.debugName : desc.blob && desc.blob->name ? desc.blob->name : "";
    Call call{"createShader", name.c_str()};
    if (!desc.blob) return fail(call, "blob: null (findShader returned no shader?)"), ShaderHandle{};
    if (!desc.blob->glsl) return fail(call, "blob has no GLSL"), ShaderHandle{};
    const ShaderBlob& blob = *desc.blob;
    if (blob.stage == ShaderStage::Compute) {
        const Limits& l = caps_.limits;
        const uint32_t* s = blob.reflection.localSize;
        for (int i = 0; i < 3; ++i)
            if (s[i] > l.maxComputeGroupSize[i])
                return fail(call, "local size " + std::to_string(s[i]) + " in dimension " + std::to_string(i) +
                                      " exceeds maxComputeGroupSize " + std::to_string(l.maxComputeGroupSize[i])),
                       ShaderHandle{};
        if (uint64_t(s[0]) * s[1] * s[2] > l.maxComputeGroupInvocations)
            return fail(call, "local size exceeds maxComputeGroupInvocations " + std::to_string(l.maxComputeGroupInvocations)),
                   ShaderHandle{};
    }
    ShaderRecord r;
    r.blob = &blob;
    r.name = name;
    std::string log;
    r.shader = compileShader(gl, shaderStageEnum(blob.stage), blob.glsl, &log);
    if (!r.shader) return fail(call, "GLSL compilation failed:\n" + log), ShaderHandle{};
    gl.ObjectLabel(GL_SHADER, r.shader, -1, name.c_str());
    if (blob.stage == ShaderStage::Compute) {
        r.program = linkProgram(gl, &r.shader, 1, &log);
        if (!r.program) {
            gl.DeleteShader(r.shader);
            return fail(call, "program link failed:\n" + log), ShaderHandle{};
        }
        gl.ObjectLabel(GL_PROGRAM, r.program, -1, name.c_str());
    }
    if (blob.stage == ShaderStage::Vertex || blob.stage == ShaderStage::Geometry)
        r.clipDistances = countClipDistances(blob.glsl);
    r.id = newId();
    ShaderHandle handle{r.id};
    shaders_.emplace(r.id, std::move(r));
    return handle;
}

TextureHandle Device::wrapNativeTexture(const TextureDesc& desc, NativeObject native) {
    makeCurrent();
    Call call{"wrapNativeTexture", desc.debugName.c_str()};
    if (!checkTextureDesc(call, desc)) return {};
    const GLuint name = GLuint(native.object);
    if (!name || !gl.IsTexture(name)) return fail(call, "native.object " + std::to_string(native.object) + " is not a GL texture"), TextureHandle{};
    GLint target = 0, immutable = 0, width = 0, height = 0, depth = 0, ifmt = 0;
    gl.GetTextureParameteriv(name, GL_TEXTURE_TARGET, &target);
    gl.GetTextureParameteriv(name, GL_TEXTURE_IMMUTABLE_FORMAT, &immutable);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_WIDTH, &width);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_HEIGHT, &height);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_DEPTH, &depth);
    gl.GetTextureLevelParameteriv(name, 0, GL_TEXTURE_INTERNAL_FORMAT, &ifmt);
    if (GLenum(target) != textureTarget(desc.dimension))
        return fail(call, "texture " + std::to_string(name) + " has target " + hex(GLenum(target)) + ", not the " +
                              textureDimensionName(desc.dimension) + " target " + hex(textureTarget(desc.dimension))),
               TextureHandle{};
    if (uint32_t(width) != desc.width || uint32_t(height) != desc.height ||
        (desc.dimension != TextureDimension::TextureCube && uint32_t(depth) != desc.depthOrLayers) ||
        GLenum(ifmt) != glFormat(desc.format).internalFormat)
        return fail(call, "texture " + std::to_string(name) + " is " + std::to_string(width) + "x" + std::to_string(height) +
                              "x" + std::to_string(depth) + " of internal format " + hex(GLenum(ifmt)) +
                              ", which does not match the description"),
               TextureHandle{};
    TextureRecord t;
    t.desc = desc;
    t.name = name;
    t.target = GLenum(target);
    t.owned = false;
    t.immutable = immutable != 0;
    t.id = newId();
    TextureHandle handle{t.id};
    textures_.emplace(t.id, std::move(t));
    return handle;
}

BufferHandle Device::wrapNativeBuffer(const BufferDesc& desc, NativeObject native) {
    makeCurrent();
    Call call{"wrapNativeBuffer", desc.debugName.c_str()};
    if (!checkBufferDesc(call, desc)) return {};
    const GLuint name = GLuint(native.object);
    if (!name || !gl.IsBuffer(name)) return fail(call, "native.object " + std::to_string(native.object) + " is not a GL buffer"), BufferHandle{};
    GLint64 size = 0;
    gl.GetNamedBufferParameteri64v(name, GL_BUFFER_SIZE, &size);
    if (uint64_t(size) < desc.size)
        return fail(call, "buffer " + std::to_string(name) + " holds " + std::to_string(size) + " bytes, less than size " +
                              std::to_string(desc.size)),
               BufferHandle{};
    BufferRecord b;
    b.desc = desc;
    b.name = name;
    b.owned = false;
    b.id = newId();
    BufferHandle handle{b.id};
    buffers_.emplace(b.id, std::move(b));
    return handle;
}

// GL defers freeing until the GPU is done with an object, which is the contract's deferred destruction.
void Device::destroy(TextureHandle h) {
    if (!h) return;
    makeCurrent();
    TextureRecord* t = texture(h, Call{"destroy"}, "texture");
    if (!t) return;
    views_.forget(gl, t->id);
    framebuffers_.forget(gl, t->id);
    if (t->owned) gl.DeleteTextures(1, &t->name);
    destroyed_[t->id] = detail::describe(*t);
    textures_.erase(t->id);
}

void Device::destroy(BufferHandle h) {
    if (!h) return;
    makeCurrent();
    BufferRecord* b = buffer(h, Call{"destroy"}, "buffer");
    if (!b) return;
    if (b->owned) gl.DeleteBuffers(1, &b->name);
    destroyed_[b->id] = detail::describe(*b);
    buffers_.erase(b->id);
}

void Device::destroy(SamplerHandle h) {
    if (!h) return;
    makeCurrent();
    SamplerRecord* s = sampler(h, Call{"destroy"}, "sampler");
    if (!s) return;
    gl.DeleteSamplers(1, &s->name);
    destroyed_[s->id] = detail::describe(*s);
    samplers_.erase(s->id);
}

void Device::destroy(ShaderHandle h) {
    if (!h) return;
    makeCurrent();
    ShaderRecord* s = shader(h, Call{"destroy"}, "shader");
    if (!s) return;
    programs_.forget(gl, s->id);
    gl.DeleteShader(s->shader);
    if (s->program) gl.DeleteProgram(s->program);
    destroyed_[s->id] = detail::describe(*s);
    shaders_.erase(s->id);
}

const TextureDesc* Device::describe(TextureHandle h) const {
    auto it = textures_.find(h.id);
    return it == textures_.end() ? nullptr : &it->second.desc;
}

const BufferDesc* Device::describe(BufferHandle h) const {
    auto it = buffers_.find(h.id);
    return it == buffers_.end() ? nullptr : &it->second.desc;
}

}  // namespace bricklight::gl::detail
