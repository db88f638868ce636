// Transfers: writes, copies, clears and read-backs. Each first issues the barrier its access needs
// against pending shader writes (BUFFER_UPDATE for buffers, TEXTURE_UPDATE for textures), so that e.g. a
// readBuffer after a dispatch that wrote the buffer sees the writes.
#include <algorithm>
#include <cmath>
#include <cstring>

#include "gl_device.h"
#include "gl_formats.h"

namespace bricklight::gl::detail {

using namespace rhi;

void Device::setPixelStore() {
    // Tight packing, row 0 first, from/to client memory: what the contract's layouts need, whatever the
    // app left in the pixel-store state.
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    gl.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    for (GLenum p : {GL_UNPACK_ALIGNMENT, GL_PACK_ALIGNMENT}) gl.PixelStorei(p, 1);
    for (GLenum p : {GL_UNPACK_ROW_LENGTH, GL_UNPACK_IMAGE_HEIGHT, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS,
                     GL_UNPACK_SKIP_IMAGES, GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST, GL_PACK_ROW_LENGTH,
                     GL_PACK_IMAGE_HEIGHT, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS, GL_PACK_SKIP_IMAGES,
                     GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST})
        gl.PixelStorei(p, 0);
}

bool Device::checkSubresource(const Call& call, const std::string& field, const TextureRecord& t,
                              const TextureSubresource& sub) const {
    if (sub.mip >= t.desc.mipLevels)
        return fail(call, field + ": mip " + std::to_string(sub.mip) + " out of range (" + detail::describe(t) + " has " +
                              std::to_string(t.desc.mipLevels) + " mips)");
    const uint32_t layers = textureLayerCount(t.desc);
    const bool layered = t.desc.dimension == TextureDimension::Texture2DArray || t.desc.dimension == TextureDimension::TextureCube;
    if (layered && (sub.layer >= layers || (sub.layerCount && uint64_t(sub.layer) + sub.layerCount > layers)))
        return fail(call, field + ": layers " + std::to_string(sub.layer) + "+" + std::to_string(sub.layerCount) +
                              " out of range (" + detail::describe(t) + " has " + std::to_string(layers) + " layers)");
    return true;
}

bool Device::checkBufferRange(const Call& call, const std::string& field, const BufferRecord& b, uint64_t offset,
                              uint64_t size) const {
    if (offset > b.desc.size || size > b.desc.size - offset)
        return fail(call, field + ": range [" + std::to_string(offset) + ", +" + std::to_string(size) +
                              ") exceeds the " + std::to_string(b.desc.size) + " bytes of " + detail::describe(b));
    return true;
}

bool Device::writeBuffer(BufferHandle h, uint64_t offset, const void* data, uint64_t size) {
    makeCurrent();
    Call call{"writeBuffer"};
    BufferRecord* b = buffer(h, call, "buffer");
    if (!b) return false;
    call.label = b->desc.debugName.c_str();
    if (!data && size) return fail(call, "data: null");
    if (!checkBufferRange(call, "offset/size", *b, offset, size)) return false;
    if (!size) return true;
    GLbitfield bits = 0;
    barriers_.require(&bits, b->lastShaderWrite, GL_BUFFER_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    // In pieces of at most 64 KiB: on NVIDIA's driver (580), a larger glNamedBufferSubData was not seen by the
    // compute dispatches that followed (the GI's 256 KiB free-slot stack read as empty); smaller ones are.
    constexpr uint64_t kPiece = 64 * 1024;
    const auto* bytes = static_cast<const uint8_t*>(data);
    for (uint64_t done = 0; done < size; done += kPiece)
        gl.NamedBufferSubData(b->name, GLintptr(offset + done), GLsizeiptr(std::min(kPiece, size - done)), bytes + done);
    return true;
}

bool Device::writeTexture(TextureHandle h, TextureSubresource sub, const void* data) {
    makeCurrent();
    Call call{"writeTexture"};
    TextureRecord* t = texture(h, call, "texture");
    if (!t) return false;
    call.label = t->desc.debugName.c_str();
    if (!data) return fail(call, "data: null");
    if (!checkSubresource(call, "sub", *t, sub)) return false;
    GLbitfield bits = 0;
    barriers_.require(&bits, t->lastShaderWrite, GL_TEXTURE_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    setPixelStore();
    return uploadTexture(*t, sub.mip, sub.layer, subresourceLayerCount(t->desc, sub), data);
}

bool Device::copyBuffer(BufferHandle dstH, uint64_t dstOffset, BufferHandle srcH, uint64_t srcOffset, uint64_t size) {
    makeCurrent();
    Call call{"copyBuffer"};
    BufferRecord* dst = buffer(dstH, call, "dst");
    BufferRecord* src = buffer(srcH, call, "src");
    if (!dst || !src) return false;
    call.label = dst->desc.debugName.c_str();
    if (!checkBufferRange(call, "dst", *dst, dstOffset, size) || !checkBufferRange(call, "src", *src, srcOffset, size))
        return false;
    if (dst == src && dstOffset < srcOffset + size && srcOffset < dstOffset + size)
        return fail(call, "source and destination ranges overlap in " + detail::describe(*dst));
    if (!size) return true;
    GLbitfield bits = 0;
    barriers_.require(&bits, dst->lastShaderWrite, GL_BUFFER_UPDATE_BARRIER_BIT);
    barriers_.require(&bits, src->lastShaderWrite, GL_BUFFER_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    gl.CopyNamedBufferSubData(src->name, dst->name, GLintptr(srcOffset), GLintptr(dstOffset), GLsizeiptr(size));
    return true;
}

bool Device::copyTexture(TextureHandle dstH, TextureSubresource dstSub, TextureHandle srcH, TextureSubresource srcSub) {
    makeCurrent();
    Call call{"copyTexture"};
    TextureRecord* dst = texture(dstH, call, "dst");
    TextureRecord* src = texture(srcH, call, "src");
    if (!dst || !src) return false;
    call.label = dst->desc.debugName.c_str();
    if (!checkSubresource(call, "dstSub", *dst, dstSub) || !checkSubresource(call, "srcSub", *src, srcSub)) return false;
    if (dst->desc.format != src->desc.format)
        return fail(call, std::string("formats differ (") + formatName(src->desc.format) + " to " +
                              formatName(dst->desc.format) + ")");
    const uint32_t w = mipExtent(src->desc.width, srcSub.mip), hgt = mipExtent(src->desc.height, srcSub.mip);
    const uint32_t depth = textureDepth(src->desc, srcSub.mip);
    const uint32_t layers = subresourceLayerCount(src->desc, srcSub);
    if (w != mipExtent(dst->desc.width, dstSub.mip) || hgt != mipExtent(dst->desc.height, dstSub.mip) ||
        depth != textureDepth(dst->desc, dstSub.mip) || layers != subresourceLayerCount(dst->desc, dstSub))
        return fail(call, "subresource sizes differ");
    if (dst == src && dstSub.mip == srcSub.mip) return fail(call, "src and dst are the same subresource");
    GLbitfield bits = 0;
    barriers_.require(&bits, dst->lastShaderWrite, GL_TEXTURE_UPDATE_BARRIER_BIT);
    barriers_.require(&bits, src->lastShaderWrite, GL_TEXTURE_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    const bool srcLayered = src->desc.dimension != TextureDimension::Texture2D && src->desc.dimension != TextureDimension::Texture3D;
    const bool dstLayered = dst->desc.dimension != TextureDimension::Texture2D && dst->desc.dimension != TextureDimension::Texture3D;
    gl.CopyImageSubData(src->name, src->target, GLint(srcSub.mip), 0, 0, srcLayered ? GLint(srcSub.layer) : 0, dst->name,
                        dst->target, GLint(dstSub.mip), 0, 0, dstLayered ? GLint(dstSub.layer) : 0, GLsizei(w),
                        GLsizei(hgt), GLsizei(src->desc.dimension == TextureDimension::Texture3D ? depth : layers));
    return true;
}

bool Device::clearBuffer(BufferHandle h, BufferRange range, uint32_t value) {
    makeCurrent();
    Call call{"clearBuffer"};
    BufferRecord* b = buffer(h, call, "buffer");
    if (!b) return false;
    call.label = b->desc.debugName.c_str();
    const uint64_t size = range.size ? range.size : (range.offset < b->desc.size ? b->desc.size - range.offset : 0);
    if (!checkBufferRange(call, "range", *b, range.offset, size)) return false;
    if (range.offset % 4 || size % 4) return fail(call, "range offset and size must be multiples of 4");
    if (!size) return true;
    GLbitfield bits = 0;
    barriers_.require(&bits, b->lastShaderWrite, GL_BUFFER_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    gl.ClearNamedBufferSubData(b->name, GL_R32UI, GLintptr(range.offset), GLsizeiptr(size), GL_RED_INTEGER,
                               GL_UNSIGNED_INT, &value);
    return true;
}

bool Device::clearTexture(TextureHandle h, uint32_t baseMip, uint32_t mipCount, ClearValue value) {
    makeCurrent();
    Call call{"clearTexture"};
    TextureRecord* t = texture(h, call, "texture");
    if (!t) return false;
    call.label = t->desc.debugName.c_str();
    if (baseMip >= t->desc.mipLevels || (mipCount && uint64_t(baseMip) + mipCount > t->desc.mipLevels))
        return fail(call, "mip range " + std::to_string(baseMip) + "+" + std::to_string(mipCount) + " out of range (" +
                              std::to_string(t->desc.mipLevels) + " mips)");
    const uint32_t count = mipCount ? mipCount : t->desc.mipLevels - baseMip;
    GLbitfield bits = 0;
    barriers_.require(&bits, t->lastShaderWrite, GL_TEXTURE_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    gl.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
    const auto kind = formatInfo(t->desc.format).kind;
    GLenum format = GL_RGBA, type = GL_FLOAT;
    const void* data = value.f;
    uint8_t srgb[4];
    switch (kind) {
        case FormatInfo::Kind::Uint: format = GL_RGBA_INTEGER, type = GL_UNSIGNED_INT, data = value.u; break;
        case FormatInfo::Kind::Sint: format = GL_RGBA_INTEGER, type = GL_INT, data = value.u; break;
        case FormatInfo::Kind::Depth: format = GL_DEPTH_COMPONENT, type = GL_FLOAT, data = value.f; break;
        case FormatInfo::Kind::Srgb:
            // Vulkan encodes a linear clear colour into sRGB; glClearTexImage would store it as given.
            for (int i = 0; i < 3; ++i) srgb[i] = linearToSrgb8(value.f[i]);
            srgb[3] = uint8_t(std::lround(std::fmin(std::fmax(value.f[3], 0.0f), 1.0f) * 255.0f));
            format = GL_RGBA, type = GL_UNSIGNED_BYTE, data = srgb;
            break;
        default: break;
    }
    for (uint32_t mip = baseMip; mip < baseMip + count; ++mip) gl.ClearTexImage(t->name, GLint(mip), format, type, data);
    return true;
}

bool Device::readBuffer(BufferHandle h, uint64_t offset, uint64_t size, void* out) {
    makeCurrent();
    Call call{"readBuffer"};
    BufferRecord* b = buffer(h, call, "buffer");
    if (!b) return false;
    call.label = b->desc.debugName.c_str();
    if (!out && size) return fail(call, "out: null");
    if (!checkBufferRange(call, "offset/size", *b, offset, size)) return false;
    if (!size) return true;
    GLbitfield bits = 0;
    barriers_.require(&bits, b->lastShaderWrite, GL_BUFFER_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    // Synchronous: GL waits for the commands that write the buffer before copying.
    gl.GetNamedBufferSubData(b->name, GLintptr(offset), GLsizeiptr(size), out);
    return true;
}

uint64_t Device::requestReadback(BufferHandle h, uint64_t offset, uint64_t size) {
    makeCurrent();
    Call call{"requestReadback"};
    BufferRecord* b = buffer(h, call, "buffer");
    if (!b) return 0;
    call.label = b->desc.debugName.c_str();
    if (!size) return fail(call, "size: 0"), 0;
    if (!checkBufferRange(call, "offset/size", *b, offset, size)) return 0;
    GLbitfield bits = 0;
    barriers_.require(&bits, b->lastShaderWrite, GL_BUFFER_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    PendingReadback rb;
    drainErrors(gl);
    gl.CreateBuffers(1, &rb.buffer);
    gl.NamedBufferStorage(rb.buffer, GLsizeiptr(size), nullptr, GL_CLIENT_STORAGE_BIT);
    if (GLenum err = gl.GetError(); err != GL_NO_ERROR) {  // the staging copy may not fit where the buffer did
        gl.DeleteBuffers(1, &rb.buffer);
        return fail(call, "cannot allocate " + std::to_string(size) + " bytes of read-back memory (GL error " + hex(err) + ")"), 0;
    }
    gl.CopyNamedBufferSubData(b->name, rb.buffer, GLintptr(offset), 0, GLsizeiptr(size));
    rb.fence = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    rb.size = size;
    const uint64_t ticket = nextReadbackTicket_++;
    readbacks_[ticket] = rb;
    return ticket;
}

ReadbackStatus Device::pollReadback(uint64_t ticket, void* out) {
    makeCurrent();
    auto it = readbacks_.find(ticket);
    if (it == readbacks_.end()) return ReadbackStatus::Failed;  // the status is the message
    PendingReadback& rb = it->second;
    // Timeout 0: only asks. GL_SYNC_FLUSH_COMMANDS_BIT makes sure the fence gets to the GPU.
    const GLenum state = gl.ClientWaitSync(rb.fence, GL_SYNC_FLUSH_COMMANDS_BIT, 0);
    if (state == GL_TIMEOUT_EXPIRED) return ReadbackStatus::Pending;
    if (state == GL_WAIT_FAILED) {
        fail(Call{"pollReadback"}, "glClientWaitSync failed for ticket " + std::to_string(ticket));
        return ReadbackStatus::Failed;
    }
    if (out) gl.GetNamedBufferSubData(rb.buffer, 0, GLsizeiptr(rb.size), out);
    gl.DeleteSync(rb.fence);
    gl.DeleteBuffers(1, &rb.buffer);
    readbacks_.erase(it);
    return ReadbackStatus::Ready;
}

bool Device::readTexture(TextureHandle h, TextureSubresource sub, void* out) {
    makeCurrent();
    Call call{"readTexture"};
    TextureRecord* t = texture(h, call, "texture");
    if (!t) return false;
    call.label = t->desc.debugName.c_str();
    if (!out) return fail(call, "out: null");
    if (!checkSubresource(call, "sub", *t, sub)) return false;
    GLbitfield bits = 0;
    barriers_.require(&bits, t->lastShaderWrite, GL_TEXTURE_UPDATE_BARRIER_BIT);
    barriers_.issue(gl, bits);
    setPixelStore();
    const GlFormat& f = glFormat(t->desc.format);
    const bool is3D = t->desc.dimension == TextureDimension::Texture3D;
    const bool layered = !is3D && t->desc.dimension != TextureDimension::Texture2D;
    const GLsizei depth = GLsizei(is3D ? textureDepth(t->desc, sub.mip) : subresourceLayerCount(t->desc, sub));
    gl.GetTextureSubImage(t->name, GLint(sub.mip), 0, 0, layered ? GLint(sub.layer) : 0,
                          GLsizei(mipExtent(t->desc.width, sub.mip)), GLsizei(mipExtent(t->desc.height, sub.mip)), depth,
                          f.pixelFormat, f.pixelType, GLsizei(subresourceBytes(t->desc, sub)), out);
    return true;
}

}  // namespace bricklight::gl::detail
