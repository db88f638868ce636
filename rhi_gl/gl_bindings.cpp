// Bindings -> GL binding points (the convention of bricklight/bindings.glsl):
//   constants slot s       -> uniform buffer binding s (bytes copied into the ring at call time)
//   texture slot s         -> texture unit s + the binding's sampler object on unit s
//   read buffer slot s     -> shader storage binding s
//   storage buffer slot s  -> shader storage binding 8 + s
//   storage image slot s   -> image unit s
// Validation follows the reflection of the call's shaders; the barrier bits are chosen per consumer.
#include <algorithm>

#include "gl_device.h"
#include "gl_formats.h"
#include "../rhi/binding_rules.h"

namespace bricklight::gl::detail {

using namespace rhi;

namespace {
const uint32_t kClassSlots[] = {kMaxConstantsSlots, kMaxTextureSlots, kMaxReadBufferSlots, kMaxStorageBufferSlots,
                                kMaxStorageImageSlots};

GLenum dimensionTarget(ResourceDimension d) {
    switch (d) {
        case ResourceDimension::Texture2DArray: return GL_TEXTURE_2D_ARRAY;
        case ResourceDimension::Texture3D: return GL_TEXTURE_3D;
        case ResourceDimension::TextureCube: return GL_TEXTURE_CUBE_MAP;
        default: return GL_TEXTURE_2D;
    }
}

GLenum imageAccess(Access a) {
    switch (a) {
        case Access::Read: return GL_READ_ONLY;
        case Access::Write: return GL_WRITE_ONLY;
        default: return GL_READ_WRITE;
    }
}
}  // namespace

bool Device::resolveView(const Call& call, const std::string& field, const TextureRecord& t, const TextureView& v,
                         ResolvedView* out) const {
    const TextureDesc& d = t.desc;
    const uint32_t layers = textureLayerCount(d);
    if (v.baseMip >= d.mipLevels || uint32_t(v.baseMip) + v.mipCount > d.mipLevels)
        return fail(call, field + ": mip range " + std::to_string(v.baseMip) + "+" + std::to_string(v.mipCount) +
                              " out of range (" + detail::describe(t) + " has " + std::to_string(d.mipLevels) + " mips)");
    if (v.baseLayer >= layers || uint32_t(v.baseLayer) + v.layerCount > layers)
        return fail(call, field + ": layer range " + std::to_string(v.baseLayer) + "+" + std::to_string(v.layerCount) +
                              " out of range (" + detail::describe(t) + " has " + std::to_string(layers) + " layers)");
    out->baseMip = v.baseMip;
    out->mipCount = v.mipCount ? v.mipCount : d.mipLevels - v.baseMip;
    out->baseLayer = v.baseLayer;
    out->layerCount = v.layerCount ? v.layerCount : layers - v.baseLayer;
    out->format = v.format == Format::Unknown ? d.format : v.format;
    if (out->format != d.format) {
        const FormatInfo& a = formatInfo(out->format);
        const FormatInfo& b = formatInfo(d.format);
        using K = FormatInfo::Kind;
        if (out->format >= Format::Count || a.bytesPerTexel != b.bytesPerTexel || a.kind == K::Depth ||
            b.kind == K::Depth)
            return fail(call, field + ": view format " + formatName(out->format) + " cannot reinterpret " +
                                  detail::describe(t) + " of format " + formatName(d.format) +
                                  " (same texel size, colour formats only)");
    }
    return true;
}

bool Device::declare(const Call& call, const ShaderRecord& shader, Declared* declared) const {
    declared->shaderNames += (declared->shaderNames.empty() ? "" : "+") + shader.name;
    const ShaderReflection& r = shader.blob->reflection;
    for (uint32_t i = 0; i < r.bindingCount; ++i) {
        const ReflectedBinding& b = r.bindings[i];
        if (b.bindingClass >= 5 || b.slot >= kClassSlots[b.bindingClass]) continue;  // the compiler rejects these
        const ReflectedBinding*& at = declared->at[b.bindingClass][b.slot];
        if (at && (at->dimension != b.dimension || at->imageFormat != b.imageFormat))
            return fail(call, std::string("stages disagree on ") + bindingClassSingular(unsigned(b.bindingClass)) + " slot " +
                                  std::to_string(b.slot) + " ('" + at->name + "' vs '" + b.name + "')");
        at = &b;
    }
    return true;
}

bool Device::resolveBindings(const Call& call, const Bindings& b, const Declared& declared, uint32_t flags,
                             BindingPlan* plan) {
    // Writers that the record calls order-independent with the previous writer get no write-after-write
    // barrier; their reads through other bindings still do.
    const bool orderIndependent = (flags & DispatchFlags::NoBarrierWithPreviousWriter) != 0;
    bool bound[5][16] = {};
    auto claim = [&](BindingClass c, size_t i, uint32_t slot) {
        if (slot >= kClassSlots[size_t(c)])
            return fail(call, slotField(c, i, slot) + ": slot out of range (max " +
                                  std::to_string(kClassSlots[size_t(c)] - 1) + ")");
        if (bound[size_t(c)][slot]) return fail(call, slotField(c, i, slot) + ": slot bound twice");
        bound[size_t(c)][slot] = true;
        return true;
    };

    for (size_t i = 0; i < b.constants.size(); ++i) {
        const ConstantsBinding& c = b.constants[i];
        if (!claim(BindingClass::Constants, i, c.slot)) return false;
        const std::string field = slotField(BindingClass::Constants, i, c.slot);
        if (!c.data || c.size == 0) return fail(call, field + ": no constant data (data null or size 0)");
        if (c.size > kMaxConstantsBytes)
            return fail(call, field + ": " + std::to_string(c.size) + " bytes exceed kMaxConstantsBytes 256");
        const ReflectedBinding* rb = declared.at[0][c.slot];
        if (!rb) continue;  // nothing reads it
        if (c.size < rb->blockSize)
            return fail(call, field + ": " + std::to_string(c.size) + " bytes given but block '" + rb->name + "' is " +
                                  std::to_string(rb->blockSize) + " bytes (std140)");
        const uint32_t bindSize = std::min<uint32_t>((std::max(c.size, rb->blockSize) + 15) / 16 * 16, kMaxConstantsBytes);
        plan->constants.push_back({c.slot, c.data, c.size, bindSize});
    }

    for (size_t i = 0; i < b.textures.size(); ++i) {
        const TextureBinding& tb = b.textures[i];
        if (!claim(BindingClass::Texture, i, tb.slot)) return false;
        std::string field = slotField(BindingClass::Texture, i, tb.slot);
        TextureRecord* t = texture(tb.view.texture, call, field + ".view.texture");
        SamplerRecord* s = sampler(tb.sampler, call, field + ".sampler");
        if (!t || !s) return false;
        field.append(" ").append(detail::describe(*t));
        ResolvedView v;
        if (!resolveView(call, field, *t, tb.view, &v)) return false;
        if (!(t->desc.usage & TextureUsage::Sampled)) return fail(call, field + ": was not created with TextureUsage::Sampled");
        if (!caps_.supports(v.format, FormatSupport::Sampled))
            return fail(call, field + ": format " + formatName(v.format) + " cannot be sampled on this device");
        // GL would silently make such a texture incomplete (it samples zeros); Vulkan rejects it.
        if ((s->desc.minFilter == Filter::Linear || s->desc.magFilter == Filter::Linear ||
             (s->desc.mipFilter == Filter::Linear && v.mipCount > 1)) &&
            !s->desc.compareEnable && !caps_.supports(v.format, FormatSupport::Filterable))
            return fail(call, field + ": format " + formatName(v.format) + " is not filterable but " +
                                  detail::describe(*s) + " uses linear filtering");
        const ReflectedBinding* rb = declared.at[1][tb.slot];
        if (!rb) continue;
        if (!dimensionCompatible(rb->dimension, t->desc.dimension, v.layerCount))
            return fail(call, field + ": shader '" + rb->name + "' is " + dimensionName(rb->dimension) + " but the view is " +
                                  textureDimensionName(t->desc.dimension) + " with " + std::to_string(v.layerCount) + " layer(s)");
        if (!scalarCompatible(rb->scalar, v.format))
            return fail(call, field + ": shader '" + rb->name + "' and view format " + formatName(v.format) +
                                  " disagree on float/int/uint");
        std::string error;
        const GLuint name = views_.get(gl, *t, dimensionTarget(rb->dimension), v, &error);
        if (!name) return fail(call, field + ": " + error);
        plan->textures.push_back({tb.slot, name, s->name});
        barriers_.require(&plan->barriers, t->lastShaderWrite, GL_TEXTURE_FETCH_BARRIER_BIT);
    }

    auto bufferBinding = [&](BindingClass c, size_t i, uint32_t slot, BufferHandle h, BufferRange range, Access access) {
        if (!claim(c, i, slot)) return false;
        std::string field = slotField(c, i, slot);
        BufferRecord* buf = buffer(h, call, field + ".buffer");
        if (!buf) return false;
        field.append(" ").append(detail::describe(*buf));
        const bool storage = c == BindingClass::StorageBuffer;
        if (!(buf->desc.usage & (storage ? BufferUsage::ShaderWrite : BufferUsage::ShaderRead)))
            return fail(call, field + ": was not created with " +
                                  (storage ? "BufferUsage::ShaderWrite" : "BufferUsage::ShaderRead"));
        const uint64_t total = buf->desc.size;
        if (range.offset >= total || (range.size && range.size > total - range.offset))
            return fail(call, field + ": out-of-range buffer view [" + std::to_string(range.offset) + ", " +
                                  std::to_string(range.offset + range.size) + ") of a " + std::to_string(total) + "-byte buffer");
        const uint64_t size = range.size ? range.size : total - range.offset;
        if (range.offset % uint64_t(storageAlignment_))
            return fail(call, field + ": offset " + std::to_string(range.offset) + " is not a multiple of " +
                                  "GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT " + std::to_string(storageAlignment_));
        if (size % 4) return fail(call, field + ": size " + std::to_string(size) + " is not a multiple of 4");
        if (size > caps_.limits.maxStorageBufferRange)
            return fail(call, field + ": range of " + std::to_string(size) + " bytes exceeds maxStorageBufferRange " +
                                  std::to_string(caps_.limits.maxStorageBufferRange));
        const ReflectedBinding* rb = declared.at[size_t(c)][slot];
        if (!rb) return true;
        if (size < rb->blockSize)
            return fail(call, field + ": " + std::to_string(size) + " bytes bound but block '" + rb->name +
                                  "' needs at least " + std::to_string(rb->blockSize));
        plan->buffers.push_back({storage ? 8u + slot : slot, buf->name, GLintptr(range.offset), GLsizeiptr(size)});
        const bool writes = storage && accessWrites(access);
        if (!(writes && orderIndependent))
            barriers_.require(&plan->barriers, buf->lastShaderWrite, GL_SHADER_STORAGE_BARRIER_BIT);
        if (writes) plan->writtenBuffers.push_back(buf);
        return true;
    };
    for (size_t i = 0; i < b.readBuffers.size(); ++i) {
        const ReadBufferBinding& rb = b.readBuffers[i];
        if (!bufferBinding(BindingClass::ReadBuffer, i, rb.slot, rb.buffer, rb.range, Access::Read)) return false;
    }
    for (size_t i = 0; i < b.storageBuffers.size(); ++i) {
        const StorageBufferBinding& sb = b.storageBuffers[i];
        if (!bufferBinding(BindingClass::StorageBuffer, i, sb.slot, sb.buffer, sb.range, sb.access)) return false;
    }

    for (size_t i = 0; i < b.storageImages.size(); ++i) {
        const StorageImageBinding& ib = b.storageImages[i];
        if (!claim(BindingClass::StorageImage, i, ib.slot)) return false;
        std::string field = slotField(BindingClass::StorageImage, i, ib.slot);
        TextureRecord* t = texture(ib.view.texture, call, field + ".view.texture");
        if (!t) return false;
        field.append(" ").append(detail::describe(*t));
        ResolvedView v;
        if (!resolveView(call, field, *t, ib.view, &v)) return false;
        if (ib.view.mipCount > 1)
            return fail(call, field + ": a storage image binds one mip (mipCount " + std::to_string(ib.view.mipCount) + ")");
        if (!(t->desc.usage & TextureUsage::Storage)) return fail(call, field + ": was not created with TextureUsage::Storage");
        if (!caps_.supports(v.format, FormatSupport::Storage))
            return fail(call, field + ": wrong format for a storage image: " + formatName(v.format) +
                                  " is not storage-capable on this device");
        if (ib.access == Access::Atomic && !caps_.supports(v.format, FormatSupport::StorageAtomic))
            return fail(call, field + ": atomic access needs an atomic-capable format (R32_UINT/R32_SINT), not " +
                                  formatName(v.format));
        const ReflectedBinding* rb = declared.at[4][ib.slot];
        if (!rb) continue;
        if (Format(rb->imageFormat) != v.format)
            return fail(call, field + ": wrong format for a storage image: shader '" + rb->name + "' declares " +
                                  formatName(Format(rb->imageFormat)) + " but the view is " + formatName(v.format));
        if (!dimensionCompatible(rb->dimension, t->desc.dimension, v.layerCount))
            return fail(call, field + ": shader '" + rb->name + "' is " + dimensionName(rb->dimension) + " but the view is " +
                                  textureDimensionName(t->desc.dimension) + " with " + std::to_string(v.layerCount) + " layer(s)");
        // The texture itself when it can be bound as is (one layer of an array as a 2D image is plain
        // glBindImageTexture); a view for a format reinterpretation or a subset of layers.
        const GLenum target = dimensionTarget(rb->dimension);
        const bool layered = rb->dimension != ResourceDimension::Texture2D;
        const bool allLayers = v.baseLayer == 0 && v.layerCount == textureLayerCount(t->desc);
        BindingPlan::Image image{ib.slot, t->name, GLint(v.baseMip), layered, 0, imageAccess(ib.access),
                                 glFormat(v.format).internalFormat};
        if (!layered) image.layer = GLint(v.baseLayer);
        if (v.format != t->desc.format || (layered && (!allLayers || t->target != target))) {
            ResolvedView one = v;
            one.mipCount = 1;
            std::string error;
            image.texture = views_.get(gl, *t, target, one, &error);
            if (!image.texture) return fail(call, field + ": " + error);
            image.level = 0;
            image.layer = 0;
        }
        plan->images.push_back(image);
        const bool writes = accessWrites(ib.access);
        if (!(writes && orderIndependent))
            barriers_.require(&plan->barriers, t->lastShaderWrite, GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        if (writes) plan->writtenTextures.push_back(t);
    }

    // Every slot the shaders declare must be bound: GL would silently read whatever is bound there.
    for (size_t c = 0; c < 5; ++c)
        for (uint32_t slot = 0; slot < kClassSlots[c]; ++slot)
            if (declared.at[c][slot] && !bound[c][slot])
                return fail(call, std::string("missing binding: shader ") + declared.shaderNames + " declares " +
                                      bindingClassSingular(unsigned(c)) + " '" + declared.at[c][slot]->name + "' at slot " +
                                      std::to_string(slot) + " but " + bindingClassName(BindingClass(c)) +
                                      " has no entry for it");
    return true;
}

void Device::applyBindings(const BindingPlan& plan) {
    for (const auto& c : plan.constants) {
        const GLintptr offset = constants_.push(gl, c.data, c.size, c.bindSize);
        gl.BindBufferRange(GL_UNIFORM_BUFFER, c.index, constants_.buffer(), offset, c.bindSize);
    }
    for (const auto& t : plan.textures) {
        gl.BindTextureUnit(t.unit, t.texture);
        gl.BindSampler(t.unit, t.sampler);
    }
    for (const auto& b : plan.buffers) gl.BindBufferRange(GL_SHADER_STORAGE_BUFFER, b.index, b.buffer, b.offset, b.size);
    for (const auto& i : plan.images)
        gl.BindImageTexture(i.unit, i.texture, i.level, i.layered, i.layer, i.access, i.format);
    gl.Enable(GL_TEXTURE_CUBE_MAP_SEAMLESS);  // Vulkan always filters cube maps seamlessly
}

void Device::finishBindings(const BindingPlan& plan) {
    if (!plan.writtenBuffers.empty() || !plan.writtenTextures.empty()) {
        const uint64_t serial = barriers_.nextWriteSerial();
        for (BufferRecord* b : plan.writtenBuffers) b->lastShaderWrite = serial;
        for (TextureRecord* t : plan.writtenTextures) t->lastShaderWrite = serial;
    }
    // No image unit stays bound: a later call (ours or the app's) may sample the same texture.
    for (const auto& i : plan.images) gl.BindImageTextures(i.unit, 1, nullptr);
}

}  // namespace bricklight::gl::detail
