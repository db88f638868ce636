// Validation of DispatchState / DrawCallState records against the reflection of their shaders: every
// declared slot bound with the right class, every binding's resource live, of the right usage, format,
// dimension and range, and no subresource bound for both reading and writing.
#include <algorithm>
#include <map>
#include <optional>

#include "validation_internal.h"
#include "binding_rules.h"
#include "size_math.h"

namespace bricklight::rhi::validation {

namespace {


// The union of the bindings declared by the stages of one call, keyed by (class, slot).
struct DeclaredBindings {
    std::map<std::pair<int, int>, const ReflectedBinding*> byClassSlot;
    uint32_t declaredInSource[5] = {};  // ShaderReflection::declaredSlots of every stage
    std::string shaderNames;

    void add(const ShaderInfo& s, Report& r) {
        if (!shaderNames.empty()) shaderNames += "+";
        shaderNames += s.name;
        const ShaderReflection& refl = s.blob->reflection;
        for (int c = 0; c < 5; ++c) declaredInSource[c] |= refl.declaredSlots[c];
        for (uint32_t i = 0; i < refl.bindingCount; ++i) {
            const ReflectedBinding& b = refl.bindings[i];
            auto key = std::make_pair(int(b.bindingClass), int(b.slot));
            auto [it, inserted] = byClassSlot.emplace(key, &b);
            if (!inserted && (it->second->dimension != b.dimension || it->second->imageFormat != b.imageFormat))
                r.error(std::string("stages disagree on ") + bindingClassSingular(unsigned(b.bindingClass)) + " slot " +
                        std::to_string(b.slot) + " ('" + it->second->name + "' vs '" + b.name + "')");
        }
    }
    const ReflectedBinding* find(BindingClass c, uint32_t slot) const {
        auto it = byClassSlot.find({int(c), int(slot)});
        return it == byClassSlot.end() ? nullptr : it->second;
    }
};

// One use of a resource by a call, for the read/write overlap check.
struct Use {
    bool isTexture;
    uint32_t id;
    uint64_t begin0, end0;  // mips (textures) or bytes (buffers)
    uint64_t begin1, end1;  // layers (textures)
    bool writes;
    std::string field;
};

struct ResolvedView {
    Format format;
    uint32_t baseMip, mipCount, baseLayer, layerCount;
};

bool resolveView(const TextureDesc& d, const TextureView& v, const std::string& field, Report& r, ResolvedView* out) {
    uint32_t layers = textureLayerCount(d);
    if (v.baseMip >= d.mipLevels || v.baseMip + v.mipCount > d.mipLevels) {
        r.error(field + ": mip range " + std::to_string(v.baseMip) + "+" + std::to_string(v.mipCount) +
                " out of range (texture '" + d.debugName + "' has " + std::to_string(d.mipLevels) + " mips)");
        return false;
    }
    if (v.baseLayer >= layers || v.baseLayer + v.layerCount > layers) {
        r.error(field + ": layer range " + std::to_string(v.baseLayer) + "+" + std::to_string(v.layerCount) +
                " out of range (texture '" + d.debugName + "' has " + std::to_string(layers) + " layers)");
        return false;
    }
    out->baseMip = v.baseMip;
    out->mipCount = v.mipCount ? v.mipCount : d.mipLevels - v.baseMip;
    out->baseLayer = v.baseLayer;
    out->layerCount = v.layerCount ? v.layerCount : layers - v.baseLayer;
    out->format = v.format == Format::Unknown ? d.format : v.format;
    if (v.format != Format::Unknown && v.format != d.format) {
        const FormatInfo& a = formatInfo(v.format);
        const FormatInfo& b = formatInfo(d.format);
        if (v.format >= Format::Count || a.bytesPerTexel != b.bytesPerTexel || a.kind == FormatInfo::Kind::Depth ||
            b.kind == FormatInfo::Kind::Depth) {
            r.error(field + ": view format " + formatName(v.format) + " cannot reinterpret texture '" + d.debugName +
                    "' of format " + formatName(d.format) + " (same texel size, colour formats only)");
            return false;
        }
    }
    return true;
}

class RecordChecker {
public:
    RecordChecker(const ObjectTable& t, const Capabilities& c, Report& r) : t_(t), caps_(c), r_(r) {}

    void check(const Bindings& b, const DeclaredBindings& declared) {
        checkDuplicates(b);
        for (size_t i = 0; i < b.constants.size(); ++i) constants(i, b.constants[i], declared);
        for (size_t i = 0; i < b.textures.size(); ++i) texture(i, b.textures[i], declared);
        for (size_t i = 0; i < b.readBuffers.size(); ++i)
            buffer(BindingClass::ReadBuffer, i, b.readBuffers[i].slot, b.readBuffers[i].buffer, b.readBuffers[i].range,
                   Access::Read, declared);
        for (size_t i = 0; i < b.storageBuffers.size(); ++i)
            buffer(BindingClass::StorageBuffer, i, b.storageBuffers[i].slot, b.storageBuffers[i].buffer,
                   b.storageBuffers[i].range, b.storageBuffers[i].access, declared);
        for (size_t i = 0; i < b.storageImages.size(); ++i) image(i, b.storageImages[i], declared);
        // Every slot the shaders declare must be bound.
        for (const auto& [key, rb] : declared.byClassSlot)
            if (!isBound(b, BindingClass(key.first), key.second))
                r_.error(std::string("missing binding: shader declares ") + bindingClassSingular(unsigned(key.first)) + " '" +
                         rb->name + "' at slot " + std::to_string(key.second) + " but " +
                         bindingClassName(BindingClass(key.first)) + " has no entry for it");
    }

    // Adds a render-target use (always a write) for the overlap check.
    void addTargetUse(TextureHandle tex, const ResolvedView& v, const std::string& field) {
        uses_.push_back({true, tex.id, v.baseMip, v.baseMip + 1u, v.baseLayer, v.baseLayer + 1u, true, field});
    }

    void checkOverlaps() {
        for (size_t i = 0; i < uses_.size(); ++i)
            for (size_t j = i + 1; j < uses_.size(); ++j) {
                const Use& a = uses_[i];
                const Use& b = uses_[j];
                if (a.isTexture != b.isTexture || a.id != b.id || !(a.writes || b.writes)) continue;
                bool overlap = a.begin0 < b.end0 && b.begin0 < a.end0 && a.begin1 < b.end1 && b.begin1 < a.end1;
                if (!overlap) continue;
                std::string what = a.isTexture ? describeTexture(t_, TextureHandle{a.id})
                                               : describeBuffer(t_, BufferHandle{a.id});
                if (a.writes && b.writes)
                    r_.error(a.field + " and " + b.field + " both write overlapping parts of " + what);
                else
                    r_.error("the same subresource is bound for read and write: " + a.field + " and " + b.field +
                             " overlap in " + what);
            }
    }

private:
    static bool isBound(const Bindings& b, BindingClass c, int slot) {
        auto has = [slot](const auto& arr) {
            return std::any_of(arr.begin(), arr.end(), [slot](const auto& e) { return e.slot == slot; });
        };
        switch (c) {
            case BindingClass::Constants: return has(b.constants);
            case BindingClass::Texture: return has(b.textures);
            case BindingClass::ReadBuffer: return has(b.readBuffers);
            case BindingClass::StorageBuffer: return has(b.storageBuffers);
            case BindingClass::StorageImage: return has(b.storageImages);
        }
        return false;
    }

    void checkDuplicates(const Bindings& b) {
        auto dup = [this](const auto& arr, BindingClass c) {
            for (size_t i = 0; i < arr.size(); ++i)
                for (size_t j = i + 1; j < arr.size(); ++j)
                    if (arr[i].slot == arr[j].slot)
                        r_.error(std::string(bindingClassName(c)) + "[" + std::to_string(i) + "] and [" +
                                 std::to_string(j) + "] both bind slot " + std::to_string(arr[i].slot));
        };
        dup(b.constants, BindingClass::Constants);
        dup(b.textures, BindingClass::Texture);
        dup(b.readBuffers, BindingClass::ReadBuffer);
        dup(b.storageBuffers, BindingClass::StorageBuffer);
        dup(b.storageImages, BindingClass::StorageImage);
    }

    // The reflected declaration for a binding; a binding to an undeclared slot is only a warning (it is
    // harmless), but it names the class the shader does declare there, which is the usual mistake.
    const ReflectedBinding* declaration(BindingClass c, size_t i, uint32_t slot, const DeclaredBindings& declared) {
        if (const ReflectedBinding* rb = declared.find(c, slot)) return rb;
        // Declared in the source but dropped by the compiler as unused: binding it is expected (shared
        // includes declare whole sets) and the backends skip it.
        if (slot < 32 && (declared.declaredInSource[int(c)] >> slot & 1u)) return nullptr;
        std::string other;
        for (int k = 0; k < 5; ++k)
            if (k != int(c) && declared.find(BindingClass(k), slot))
                other = std::string(" (it declares a ") + bindingClassSingular(unsigned(k)) + " at slot " + std::to_string(slot) +
                        ": wrong binding class?)";
        r_.warning(slotField(c, i, slot) + ": shader " + declared.shaderNames + " declares no " +
                   bindingClassSingular(unsigned(int(c))) + " at this slot" + other);
        return nullptr;
    }

    void constants(size_t i, const ConstantsBinding& b, const DeclaredBindings& declared) {
        std::string field = slotField(BindingClass::Constants, i, b.slot);
        const ReflectedBinding* rb = declaration(BindingClass::Constants, i, b.slot, declared);
        if (!b.data || b.size == 0) r_.error(field + ": no constant data (data null or size 0)");
        if (b.size > kMaxConstantsBytes)
            r_.error(field + ": " + std::to_string(b.size) + " bytes exceed kMaxConstantsBytes " +
                     std::to_string(kMaxConstantsBytes));
        if (rb && b.size < rb->blockSize)
            r_.error(field + ": " + std::to_string(b.size) + " bytes given but block '" + rb->name + "' is " +
                     std::to_string(rb->blockSize) + " bytes (std140)");
    }

    void texture(size_t i, const TextureBinding& b, const DeclaredBindings& declared) {
        std::string field = slotField(BindingClass::Texture, i, b.slot);
        const ReflectedBinding* rb = declaration(BindingClass::Texture, i, b.slot, declared);
        const TextureDesc* d = liveTexture(t_, b.view.texture, field + ".view.texture", r_);
        const SamplerDesc* s = liveSampler(t_, b.sampler, field + ".sampler", r_);
        if (!d) return;
        field += " " + describeTexture(t_, b.view.texture);
        ResolvedView v;
        if (!resolveView(*d, b.view, field, r_, &v)) return;
        if (!(d->usage & TextureUsage::Sampled)) r_.error(field + ": was not created with TextureUsage::Sampled");
        if (!caps_.supports(v.format, FormatSupport::Sampled))
            r_.error(field + ": format " + formatName(v.format) + " cannot be sampled on this device");
        if (s && (s->minFilter == Filter::Linear || s->magFilter == Filter::Linear ||
                  (s->mipFilter == Filter::Linear && v.mipCount > 1)) &&
            !caps_.supports(v.format, FormatSupport::Filterable) && !s->compareEnable)
            r_.error(field + ": format " + formatName(v.format) + " is not filterable but sampler uses linear filtering");
        if (rb) {
            if (!dimensionCompatible(rb->dimension, d->dimension, v.layerCount))
                r_.error(field + ": shader '" + rb->name + "' is " + dimensionName(rb->dimension) + " but the view is " +
                         textureDimensionName(d->dimension) + " with " + std::to_string(v.layerCount) + " layer(s)");
            if (!scalarCompatible(rb->scalar, v.format))
                r_.error(field + ": shader '" + rb->name + "' samples " +
                         (rb->scalar == ResourceScalar::Uint ? "uint" : rb->scalar == ResourceScalar::Sint ? "int" : "float") +
                         " values but the view format is " + formatName(v.format));
            if (rb->shadow && (!s || !s->compareEnable || formatInfo(v.format).kind != FormatInfo::Kind::Depth))
                r_.error(field + ": shader '" + rb->name + "' is a shadow sampler: needs a depth format and a compare sampler");
        }
        uses_.push_back({true, b.view.texture.id, v.baseMip, v.baseMip + v.mipCount, v.baseLayer,
                         v.baseLayer + v.layerCount, false, field});
    }

    void buffer(BindingClass c, size_t i, uint32_t slot, BufferHandle h, BufferRange range, Access access,
                const DeclaredBindings& declared) {
        std::string field = slotField(c, i, slot);
        const ReflectedBinding* rb = declaration(c, i, slot, declared);
        const BufferDesc* d = liveBuffer(t_, h, field + ".buffer", r_);
        if (!d) return;
        field += " " + describeBuffer(t_, h);
        uint32_t needUsage = c == BindingClass::ReadBuffer ? BufferUsage::ShaderRead : BufferUsage::ShaderWrite;
        if (!(d->usage & needUsage))
            r_.error(field + ": was not created with " +
                     (c == BindingClass::ReadBuffer ? "BufferUsage::ShaderRead" : "BufferUsage::ShaderWrite"));
        if (range.offset >= d->size || (range.size && range.size > d->size - range.offset)) {
            r_.error(field + ": out-of-range buffer view [" + std::to_string(range.offset) + ", " +
                     std::to_string(range.offset + range.size) + ") of a " + std::to_string(d->size) + "-byte buffer");
            return;
        }
        uint64_t size = range.size ? range.size : d->size - range.offset;
        uint32_t align = std::max(caps_.limits.minStorageBufferOffsetAlignment, 4u);
        if (range.offset % align)
            r_.error(field + ": offset " + std::to_string(range.offset) + " is not a multiple of " +
                     "minStorageBufferOffsetAlignment " + std::to_string(align));
        if (d->structStride && range.offset % d->structStride)
            r_.error(field + ": offset is not a multiple of structStride " + std::to_string(d->structStride));
        if (size % 4) r_.error(field + ": size " + std::to_string(size) + " is not a multiple of 4");
        if (caps_.limits.maxStorageBufferRange && size > caps_.limits.maxStorageBufferRange)
            r_.error(field + ": range of " + std::to_string(size) + " bytes exceeds maxStorageBufferRange");
        if (rb && size < rb->blockSize)
            r_.error(field + ": " + std::to_string(size) + " bytes bound but block '" + rb->name + "' needs at least " +
                     std::to_string(rb->blockSize));
        if (c == BindingClass::StorageBuffer && rb && rb->readOnly && accessWrites(access))
            r_.error(field + ": declared " + accessName(access) + " but the shader's block is readonly");
        uses_.push_back({false, h.id, range.offset, range.offset + size, 0, 1, accessWrites(access), field});
    }

    void image(size_t i, const StorageImageBinding& b, const DeclaredBindings& declared) {
        std::string field = slotField(BindingClass::StorageImage, i, b.slot);
        const ReflectedBinding* rb = declaration(BindingClass::StorageImage, i, b.slot, declared);
        const TextureDesc* d = liveTexture(t_, b.view.texture, field + ".view.texture", r_);
        if (!d) return;
        field += " " + describeTexture(t_, b.view.texture);
        ResolvedView v;
        if (!resolveView(*d, b.view, field, r_, &v)) return;
        if (b.view.mipCount > 1)
            r_.error(field + ": a storage image binds one mip (mipCount " + std::to_string(b.view.mipCount) + ")");
        if (!(d->usage & TextureUsage::Storage)) r_.error(field + ": was not created with TextureUsage::Storage");
        if (!caps_.supports(v.format, FormatSupport::Storage))
            r_.error(field + ": wrong format for a storage image: " + formatName(v.format) +
                     " is not storage-capable on this device");
        if (b.access == Access::Atomic && !caps_.supports(v.format, FormatSupport::StorageAtomic))
            r_.error(field + ": atomic access needs an atomic-capable format (R32_UINT/R32_SINT), not " +
                     formatName(v.format));
        if (rb) {
            Format declaredFormat = Format(rb->imageFormat);
            if (declaredFormat != v.format)
                r_.error(field + ": wrong format for a storage image: shader '" + rb->name + "' declares " +
                         formatName(declaredFormat) + " but the view is " + formatName(v.format));
            if (!dimensionCompatible(rb->dimension, d->dimension, v.layerCount))
                r_.error(field + ": shader '" + rb->name + "' is " + dimensionName(rb->dimension) + " but the view is " +
                         textureDimensionName(d->dimension) + " with " + std::to_string(v.layerCount) + " layer(s)");
            if (rb->readOnly && accessWrites(b.access))
                r_.error(field + ": declared " + accessName(b.access) + " but the shader's image is readonly");
            if (rb->writeOnly && b.access != Access::Write)
                r_.error(field + ": declared " + accessName(b.access) + " but the shader's image is writeonly (use Access::Write)");
        }
        uses_.push_back({true, b.view.texture.id, v.baseMip, v.baseMip + 1u, v.baseLayer, v.baseLayer + v.layerCount,
                         accessWrites(b.access), field});
    }

    const ObjectTable& t_;
    const Capabilities& caps_;
    Report& r_;
    std::vector<Use> uses_;

    friend void validation::checkDraw(const ObjectTable&, const Capabilities&, const DrawCallState&, Report&);
};

// Enum fields hold a value of their enum: a record made by a cast (or decoded from a file) may not.
template <typename E>
void checkEnum(E value, int count, const std::string& field, Report& r) {
    if (int(value) >= count) r.error(field + ": " + std::to_string(int(value)) + " is out of range (0.." + std::to_string(count - 1) + ")");
}

// A FixedVector's count is a public field: one above the capacity would make every loop read past it.
template <typename V>
bool countFits(const V& v, const char* field, Report& r) {
    if (v.count <= V::capacity) return true;
    r.error(std::string(field) + ": count " + std::to_string(v.count) + " exceeds the capacity " + std::to_string(V::capacity));
    return false;
}
bool countsFit(const Bindings& b, Report& r) {
    const size_t before = r.errors.size();
    countFits(b.constants, "constants", r), countFits(b.textures, "textures", r);
    countFits(b.readBuffers, "readBuffers", r), countFits(b.storageBuffers, "storageBuffers", r);
    countFits(b.storageImages, "storageImages", r);
    return r.errors.size() == before;
}

void checkAccessEnums(const Bindings& b, Report& r) {
    for (size_t i = 0; i < b.storageBuffers.size(); ++i)
        checkEnum(b.storageBuffers[i].access, 4, slotField(BindingClass::StorageBuffer, i, b.storageBuffers[i].slot) + ".access", r);
    for (size_t i = 0; i < b.storageImages.size(); ++i)
        checkEnum(b.storageImages[i].access, 4, slotField(BindingClass::StorageImage, i, b.storageImages[i].slot) + ".access", r);
}

void checkDrawEnums(const DrawCallState& s, Report& r) {
    checkEnum(s.topology, 4, "topology", r);
    checkEnum(s.indexBuffer.format, 2, "indexBuffer.format", r);
    checkEnum(s.raster.cull, 3, "raster.cull", r);
    checkEnum(s.raster.frontFace, 2, "raster.frontFace", r);
    checkEnum(s.depth.compare, 8, "depth.compare", r);
    checkEnum(s.depthTarget.load, 3, "depthTarget.load", r);
    for (size_t i = 0; i < s.vertexInputs.size(); ++i)
        checkEnum(s.vertexInputs[i].format, 7, "vertexInputs[" + std::to_string(i) + "].format", r);
    for (size_t i = 0; i < s.colorTargets.size(); ++i) {
        const ColorTarget& c = s.colorTargets[i];
        const std::string field = "colorTargets[" + std::to_string(i) + "]";
        checkEnum(c.load, 3, field + ".load", r);
        checkEnum(c.blend.srcColor, 10, field + ".blend.srcColor", r);
        checkEnum(c.blend.dstColor, 10, field + ".blend.dstColor", r);
        checkEnum(c.blend.srcAlpha, 10, field + ".blend.srcAlpha", r);
        checkEnum(c.blend.dstAlpha, 10, field + ".blend.dstAlpha", r);
        checkEnum(c.blend.colorOp, 5, field + ".blend.colorOp", r);
        checkEnum(c.blend.alphaOp, 5, field + ".blend.alphaOp", r);
    }
}
}  // namespace

void checkDispatch(const ObjectTable& t, const Capabilities& caps, const DispatchState& s, Report& r) {
    if (!countsFit(s.bindings, r)) return;
    checkAccessEnums(s.bindings, r);
    const ShaderInfo* sh = liveShader(t, s.shader, "shader", r);
    if (!sh) return;
    if (sh->blob->stage != ShaderStage::Compute) {
        r.error("shader '" + sh->name + "' is not a compute shader");
        return;
    }
    DeclaredBindings declared;
    declared.add(*sh, r);
    RecordChecker checker(t, caps, r);
    checker.check(s.bindings, declared);
    checker.checkOverlaps();
}

void checkDraw(const ObjectTable& t, const Capabilities& caps, const DrawCallState& s, Report& r) {
    const size_t before = r.errors.size();
    countsFit(s.bindings, r);
    countFits(s.vertexInputs, "vertexInputs", r), countFits(s.vertexBuffers, "vertexBuffers", r);
    countFits(s.colorTargets, "colorTargets", r);
    if (r.errors.size() != before) return;
    checkAccessEnums(s.bindings, r);
    checkDrawEnums(s, r);
    DeclaredBindings declared;
    const ShaderInfo* vs = liveShader(t, s.vertexShader, "vertexShader", r);
    if (vs && vs->blob->stage != ShaderStage::Vertex) r.error("vertexShader '" + vs->name + "' is not a vertex shader");
    const ShaderInfo* gs = nullptr;
    const ShaderInfo* fs = nullptr;
    if (s.geometryShader) {
        gs = liveShader(t, s.geometryShader, "geometryShader", r);
        if (gs && gs->blob->stage != ShaderStage::Geometry)
            r.error("geometryShader '" + gs->name + "' is not a geometry shader");
    }
    if (s.fragmentShader) {
        fs = liveShader(t, s.fragmentShader, "fragmentShader", r);
        if (fs && fs->blob->stage != ShaderStage::Fragment)
            r.error("fragmentShader '" + fs->name + "' is not a fragment shader");
    }
    if (!r.errors.empty()) return;
    for (const ShaderInfo* sh : {vs, gs, fs})
        if (sh) declared.add(*sh, r);
    RecordChecker checker(t, caps, r);
    checker.check(s.bindings, declared);

    // Vertex inputs.
    const ShaderReflection& vr = vs->blob->reflection;
    for (uint32_t i = 0; i < vr.vertexInputCount; ++i) {
        const ReflectedVertexInput& in = vr.vertexInputs[i];
        auto it = std::find_if(s.vertexInputs.begin(), s.vertexInputs.end(),
                               [&](const VertexInput& v) { return v.location == in.location; });
        if (it == s.vertexInputs.end()) {
            r.error("missing vertex input: shader '" + vs->name + "' reads '" + in.name + "' at location " +
                    std::to_string(in.location));
            continue;
        }
        bool intInput = it->format == VertexFormat::UInt1;
        if (intInput != (in.scalar == ResourceScalar::Uint || in.scalar == ResourceScalar::Sint))
            r.error("vertexInputs location " + std::to_string(in.location) + ": integer/float mismatch with '" +
                    in.name + "'");
    }
    for (size_t i = 0; i < s.vertexInputs.size(); ++i)
        if (s.vertexInputs[i].bufferIndex >= s.vertexBuffers.size())
            r.error("vertexInputs[" + std::to_string(i) + "].bufferIndex " +
                    std::to_string(s.vertexInputs[i].bufferIndex) + " has no vertexBuffers entry");
    for (size_t i = 0; i < s.vertexBuffers.size(); ++i) {
        std::string field = "vertexBuffers[" + std::to_string(i) + "]";
        const BufferDesc* d = liveBuffer(t, s.vertexBuffers[i].buffer, field, r);
        if (!d) continue;
        if (!(d->usage & BufferUsage::Vertex)) r.error(field + ": buffer '" + d->debugName + "' lacks BufferUsage::Vertex");
        if (s.vertexBuffers[i].offset >= d->size) r.error(field + ": offset beyond the end of the buffer");
        if (s.vertexBuffers[i].stride == 0) r.error(field + ": stride is 0");
        checker.uses_.push_back({false, s.vertexBuffers[i].buffer.id, 0, d->size, 0, 1, false, field});
    }

    // Targets: all the same size, renderable, and not also bound for reading.
    if (s.colorTargets.empty() && !s.depthTarget.view.texture)
        r.error("no colour or depth target: a draw needs at least one");
    uint32_t width = 0, height = 0;
    auto sameSize = [&](const TextureDesc& d, uint32_t mip, const std::string& field) {
        uint32_t w = mipExtent(d.width, mip), h = mipExtent(d.height, mip);
        if (!width) width = w, height = h;
        else if (w != width || h != height)
            r.error(field + ": size " + std::to_string(w) + "x" + std::to_string(h) + " differs from the other targets (" +
                    std::to_string(width) + "x" + std::to_string(height) + ")");
    };
    for (size_t i = 0; i < s.colorTargets.size(); ++i) {
        const ColorTarget& ct = s.colorTargets[i];
        std::string field = "colorTargets[" + std::to_string(i) + "]";
        const TextureDesc* d = liveTexture(t, ct.view.texture, field + ".view.texture", r);
        if (!d) continue;
        ResolvedView v;
        if (!resolveView(*d, ct.view, field, r, &v)) continue;
        if (d->dimension == TextureDimension::Texture3D) r.error(field + ": a 3D texture cannot be a colour target");
        if (!(d->usage & TextureUsage::RenderTarget))
            r.error(field + ": texture '" + d->debugName + "' was not created with TextureUsage::RenderTarget");
        if (!caps.supports(v.format, FormatSupport::RenderTarget))
            r.error(field + ": format " + formatName(v.format) + " is not renderable on this device");
        if (ct.blend.enable && !caps.supports(v.format, FormatSupport::Blendable))
            r.error(field + ": blending enabled but format " + formatName(v.format) + " is not blendable");
        sameSize(*d, v.baseMip, field);
        checker.addTargetUse(ct.view.texture, v, field);
    }
    if (fs) {
        uint32_t mask = fs->blob->reflection.colorOutputMask;
        for (uint32_t loc = 0; loc < 32; ++loc)
            if ((mask & (1u << loc)) && loc >= s.colorTargets.size())
                r.warning("fragment shader '" + fs->name + "' writes location " + std::to_string(loc) +
                          " but there is no colorTargets[" + std::to_string(loc) + "]");
    }
    if (s.depthTarget.view.texture) {
        const TextureDesc* d = liveTexture(t, s.depthTarget.view.texture, "depthTarget.view.texture", r);
        ResolvedView v;
        if (d && resolveView(*d, s.depthTarget.view, "depthTarget", r, &v)) {
            if (formatInfo(v.format).kind != FormatInfo::Kind::Depth)
                r.error("depthTarget: format " + std::string(formatName(v.format)) + " is not a depth format");
            if (!(d->usage & TextureUsage::DepthTarget))
                r.error("depthTarget: texture '" + d->debugName + "' was not created with TextureUsage::DepthTarget");
            sameSize(*d, v.baseMip, "depthTarget");
            checker.addTargetUse(s.depthTarget.view.texture, v, "depthTarget");
        }
    } else if (s.depth.testEnable || s.depth.writeEnable) {
        r.error("depth test or write enabled without a depthTarget");
    }
    checker.checkOverlaps();
}

namespace {

// Elements first .. first + count - 1 of every vertex buffer of the given rate, against the buffer's size: one
// message per buffer, for the input that reads furthest.
void checkFetchRange(const ObjectTable& t, const DrawCallState& s, uint32_t first, uint32_t count, bool perInstance, Report& r) {
    if (!count) return;
    for (size_t b = 0; b < s.vertexBuffers.size(); ++b) {
        const VertexBufferBinding& vb = s.vertexBuffers[b];
        if (vb.perInstance != perInstance) continue;
        std::optional<uint64_t> furthest = 0;
        uint32_t location = 0;
        for (const VertexInput& in : s.vertexInputs) {
            if (in.bufferIndex != b) continue;
            const auto end = sizes::fetchEnd(vb.offset + in.offset, first, count, vb.stride, sizes::vertexFormatBytes(in.format));
            if (furthest && (!end || *end > *furthest)) furthest = end, location = in.location;
        }
        const BufferDesc* d = liveBuffer(t, vb.buffer, "vertexBuffers[" + std::to_string(b) + "]", r);
        if (!d || (furthest && *furthest <= d->size)) continue;
        r.error(std::string(perInstance ? "instances " : "vertices ") + std::to_string(first) + ".." + std::to_string(uint64_t(first) + count - 1) +
                " read past the end of vertexBuffers[" + std::to_string(b) + "] " + describeBuffer(t, vb.buffer) + " (" +
                std::to_string(d->size) + " bytes; location " + std::to_string(location) + " reads " +
                (furthest ? "up to byte " + std::to_string(*furthest) : std::string("beyond 2^64")) + ")");
    }
}

}  // namespace

void checkDrawFetch(const ObjectTable& t, const DrawCallState& s, const DrawArgs& a, Report& r) {
    checkFetchRange(t, s, a.firstVertex, a.vertexCount, false, r);
    checkFetchRange(t, s, a.firstInstance, a.instanceCount, true, r);
}

void checkDrawFetch(const ObjectTable& t, const DrawCallState& s, const DrawIndexedArgs& a, Report& r) {
    checkFetchRange(t, s, a.firstInstance, a.instanceCount, true, r);
    const BufferDesc* d = liveBuffer(t, s.indexBuffer.buffer, "indexBuffer.buffer", r);
    if (!d || !a.indexCount) return;
    const uint32_t bytes = s.indexBuffer.format == IndexFormat::U16 ? 2 : 4;
    const auto end = sizes::fetchEnd(s.indexBuffer.offset, a.firstIndex, a.indexCount, bytes, bytes);
    if (!end || *end > d->size)
        r.error("indices " + std::to_string(a.firstIndex) + ".." + std::to_string(uint64_t(a.firstIndex) + a.indexCount - 1) +
                " read past the end of indexBuffer " + describeBuffer(t, s.indexBuffer.buffer) + " (" + std::to_string(d->size) + " bytes)");
}

}  // namespace bricklight::rhi::validation
