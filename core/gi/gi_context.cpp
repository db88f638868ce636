#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>

#include "bricklight/half.h"
#include "../common/core_shaders.h"
#include "gi_context_impl.h"

namespace bricklight::gi {

float internalScale(InternalResolution r) {
    switch (r) {
        case InternalResolution::Native: return 1.0f;
        case InternalResolution::Percent75: return 0.75f;
        case InternalResolution::Percent50: return 0.5f;
        case InternalResolution::Percent25: return 0.25f;
    }
    return 1.0f;
}

std::unique_ptr<GiContext> GiContext::create(rhi::IDevice& device, const sdf::SdfScene& scene, const ContextDesc& desc,
                                             Error* error) {
    auto context = std::make_unique<detail::GiContextImpl>(device, scene, desc);
    if (!context->init(error)) return nullptr;
    return context;
}

namespace detail {

bool GiContextImpl::fail(ErrorCode code, const std::string& message) {
    log_.report(desc_.errorCallback, rhi::Severity::Error, code, message);
    return false;
}

void GiContextImpl::warnOnce(ErrorCode code, const std::string& message) {
    log_.report(desc_.errorCallback, rhi::Severity::Warning, code, message);
}

bool GiContextImpl::sceneAlive() {
    if (!sceneToken_.expired()) return true;
    return fail(ErrorCode::DependencyDestroyed,
                "the sdf::SdfScene this context follows was destroyed; destroy the GiContext first (or create a new one)");
}

bool GiContextImpl::init(Error* error) {
    auto bad = [&](ErrorCode code, const std::string& m) {
        fail(code, m);
        if (error) *error = lastError();
        return false;
    };
    if (desc_.displayWidth == 0 || desc_.displayHeight == 0 || desc_.displayWidth > 16384 || desc_.displayHeight > 16384)
        return bad(ErrorCode::InvalidArgument, "display size " + std::to_string(desc_.displayWidth) + "x" + std::to_string(desc_.displayHeight) +
                   " is not in 1..16384");
    if (uint32_t(desc_.internalResolution) > uint32_t(InternalResolution::Percent25))
        return bad(ErrorCode::InvalidArgument, "internalResolution " + std::to_string(uint32_t(desc_.internalResolution)) + " is not one of the four scales");
    if (desc_.flags & ~uint32_t(ContextFlags::NoSpecular | ContextFlags::NoDenoiser | ContextFlags::ReversedDepth | ContextFlags::NoCameraCheck |
                                    ContextFlags::AlphaCache | ContextFlags::NoProbeParallax))
        return bad(ErrorCode::InvalidArgument, "unknown flag bits in flags");
    if (desc_.injectTile != 0 && desc_.injectTile != 1 && desc_.injectTile != 2 && desc_.injectTile != 4 && desc_.injectTile != 8)
        return bad(ErrorCode::InvalidArgument, "injectTile " + std::to_string(desc_.injectTile) + " is not 0 (automatic), 1, 2, 4 or 8");
    if (desc_.probeTile != 0 && desc_.probeTile != 8 && desc_.probeTile != 16)
        return bad(ErrorCode::InvalidArgument, "probeTile " + std::to_string(desc_.probeTile) + " is not 0 (automatic), 8 or 16");
    const rhi::Capabilities& caps = device_.capabilities();
    using F = rhi::Format;
    for (F f : {F::R32_FLOAT, F::R32_UINT, F::RG16_FLOAT, F::R8_UNORM, F::RGBA16_FLOAT})
        if (!caps.supports(f, rhi::FormatSupport::Storage | rhi::FormatSupport::Sampled))
            return bad(ErrorCode::Unsupported, std::string("the device cannot use ") + rhi::formatName(f) + " as a storage image and a texture");
    const float scale = internalScale(desc_.internalResolution);
    width_ = std::max(1u, uint32_t(std::lround(desc_.displayWidth * scale)));
    height_ = std::max(1u, uint32_t(std::lround(desc_.displayHeight * scale)));
    probeTile_ = desc_.probeTile ? desc_.probeTile : probeTileFor(width_);
    tilesX_ = (width_ + probeTile_ - 1) / probeTile_;
    tilesY_ = (height_ + probeTile_ - 1) / probeTile_;
    injectTile_ = desc_.injectTile ? desc_.injectTile : injectTileFor(width_);
    const uint32_t capacity = scene_.brickCapacity();
    if (desc_.radianceCacheBricks > capacity)
        return bad(ErrorCode::OverBudget, "radianceCacheBricks " + std::to_string(desc_.radianceCacheBricks) + " is more than the scene's " +
                   std::to_string(capacity) + " bricks");
    cacheSlots_ = desc_.radianceCacheBricks ? desc_.radianceCacheBricks : std::min(capacity, kDefaultCacheSlots);
    cacheDepth_ = (cacheSlots_ + kCacheSlotsPerLayer - 1) / kCacheSlotsPerLayer * kCacheTexelsPerBrick;
    if (cacheDepth_ > caps.limits.maxTextureSize3D || 256 > caps.limits.maxTextureSize3D)
        return bad(ErrorCode::Unsupported, "the radiance cache (256x256x" + std::to_string(cacheDepth_) + ") exceeds the device's 3D texture limit");

    shaders::link_bricklight_gi();
    auto shader = [&](const char* name) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        return sd.blob ? device_.createShader(sd) : rhi::ShaderHandle{};
    };
    shaders_.downsample = shader("gi/downsample.comp");
    shaders_.clearFreed = shader("gi/clear_freed_bricks.comp");
    shaders_.inject = shader("gi/inject_radiance.comp");
    shaders_.propagate = shader("gi/propagate_sh.comp");
    shaders_.spawn = shader("gi/spawn_probes.comp");
    shaders_.reprojectProbes = shader("gi/reproject_probes.comp");
    // Without the parallax test no texel is marked: the variant without the marked texels' second round.
    const bool parallax = !(desc_.flags & ContextFlags::NoProbeParallax);
    shaders_.fill = shader(parallax ? "gi/fill_probes.comp" : "gi/fill_probes_carried.comp");
    shaders_.fillVct = shader(parallax ? "gi/fill_probes_vct.comp" : "gi/fill_probes_vct_carried.comp");
    shaders_.pretrace = shader("gi/specular_pretrace.comp");
    shaders_.relight = shader("gi/relight_cache.comp");
    shaders_.reprojectGi = shader("gi/reproject_gi.comp");
    shaders_.specularTrace = shader("gi/specular_trace.comp");
    shaders_.reflectionTrace = shader("gi/reflection_trace.comp");
    shaders_.project = shader("gi/project_probes.comp");
    shaders_.emit = shader("gi/emit_irradiance.comp");
    shaders_.probeWorld = shader("gi/probe_world_sh.comp");
    shaders_.interpolate = shader("gi/interpolate.comp");
    shaders_.blur = shader("gi/blur.comp");
    shaders_.upsample = shader("gi/upsample.comp");
    shaders_.debug = shader("gi/debug_view.comp");
    shaders_.cameraCheck = shader("gi/camera_check.comp");
    const bool alphaCache = (desc_.flags & ContextFlags::AlphaCache) != 0;
    if (alphaCache && !caps.geometryShader)
        return bad(ErrorCode::Unsupported, "ContextFlags::AlphaCache: the alpha pass needs geometry shaders, which the device does not offer");
    if (alphaCache) shaders_.alphaPass = shader("gi/alpha_pass.geom");

    using namespace rhi::TextureUsage;
    auto texture = [&](const std::string& name, F format, uint32_t w, uint32_t h, uint32_t usage = Sampled | Storage) {
        rhi::TextureDesc d;
        d.format = format;
        d.width = w;
        d.height = h;
        d.usage = usage;
        d.debugName = desc_.debugName + " " + name;
        return device_.createTexture(d);
    };
    for (int i = 0; i < 2; ++i) {
        const std::string s = std::to_string(i);
        depth_[i] = texture("depth" + s, F::R32_FLOAT, width_, height_);
        surface_[i] = texture("surface" + s, F::R32_UINT, width_, height_);
        probes_[i] = texture("probes" + s, F::RGBA16_FLOAT, tilesX_ * kProbeTexels, tilesY_ * kProbeTexels);
        diffuseHistory_[i] = texture("diffuseHistory" + s, F::RGBA16_FLOAT, width_, height_);
        specularHistory_[i] = texture("specularHistory" + s, F::RGBA16_FLOAT, width_, height_);
    }
    motion_ = texture("motion", F::RG16_FLOAT, width_, height_);
    disocclusion_ = texture("disocclusion", F::R8_UNORM, width_, height_);
    pretrace_ = texture("specularPretrace", F::R32_UINT, (width_ + kPretraceTile - 1) / kPretraceTile,
                        (height_ + kPretraceTile - 1) / kPretraceTile);
    specularTraced_ = texture("specularTraced", F::RGBA16_FLOAT, width_, height_);
    if (!(desc_.flags & ContextFlags::NoDenoiser)) {
        resolvedDiffuse_ = texture("resolvedDiffuse", F::RGBA16_FLOAT, width_, height_);
        resolvedSpecular_ = texture("resolvedSpecular", F::RGBA16_FLOAT, width_, height_);
    }
    dummyStorage_ = texture("unusedSpecularOutput", F::RGBA16_FLOAT, 1, 1);
    black2D_ = texture("noEnvironment2D", F::RGBA16_FLOAT, 1, 1, Sampled);
    {
        rhi::TextureDesc d;
        d.dimension = rhi::TextureDimension::TextureCube;
        d.format = F::RGBA16_FLOAT;
        d.depthOrLayers = 6;
        d.usage = Sampled;
        d.debugName = desc_.debugName + " noEnvironmentCube";
        const std::vector<uint16_t> zeros(6 * 4, 0);
        blackCube_ = device_.createTexture(d, zeros.data());
        const std::vector<uint16_t> zero(4, 0);
        if (black2D_) device_.writeTexture(black2D_, {}, zero.data());
    }
    {
        rhi::TextureDesc d;
        d.dimension = rhi::TextureDimension::Texture3D;
        d.format = F::R32_UINT;
        d.width = d.height = 64 * kCacheTexelsPerBrick;
        d.depthOrLayers = cacheDepth_;
        d.usage = Storage;
        d.debugName = desc_.debugName + " radianceCache";
        radianceCache_ = device_.createTexture(d);
    }
    auto buffer = [&](const std::string& name, uint64_t size, const void* data = nullptr, uint32_t extraUsage = 0) {
        rhi::BufferDesc d;
        d.size = size;
        d.usage |= extraUsage;
        d.debugName = desc_.debugName + " " + name;
        return device_.createBuffer(d, data);
    };
    const uint64_t tiles = uint64_t(tilesX_) * tilesY_;
    probeInfo_[0] = buffer("probeInfo0", tiles * 16);
    probeInfo_[1] = buffer("probeInfo1", tiles * 16);
    probeSH_ = buffer("probeSH", tiles * kShCoefficients * 16);
    probeIrradianceSH_ = buffer("probeIrradianceSH", tiles * kShCoefficients * 16);
    probeWorldSH_ = buffer("probeWorldSH", tiles * kShCoefficients * 16);
    brickSH_ = buffer("brickSH", uint64_t(capacity) * kShCoefficients * 8);
    const std::vector<uint32_t> noOwner(capacity, 0xFFFFFFFFu);
    cacheOwners_ = buffer("cacheOwners", uint64_t(capacity) * 4, noOwner.data());
    brickMaterial_ = buffer("brickMaterial", uint64_t(capacity) * kBrickMaterialWords * 4);
    // Two relight lists: a frame appends to one (clear_freed_bricks.comp, which also empties the other for the
    // next frame) while the relight pass reads it; no upload per frame.
    std::vector<uint32_t> list(4 + kRelightBudget, 0);
    std::copy(std::begin(kEmptyRelightList), std::end(kEmptyRelightList), list.begin());
    relightList_[0] = buffer("relightList0", 16 + uint64_t(kRelightBudget) * 4, list.data(), rhi::BufferUsage::IndirectArgs);
    relightList_[1] = buffer("relightList1", 16 + uint64_t(kRelightBudget) * 4, list.data(), rhi::BufferUsage::IndirectArgs);
    lights_ = buffer("lights", uint64_t(kMaxLights) * sizeof(GpuLight));
    slotOfBrick_ = buffer("cacheSlotOfBrick", uint64_t(capacity) * 4);
    freeSlots_ = buffer("cacheFreeSlots", 4 + uint64_t(cacheSlots_) * 4);
    cameraCheck_.counts = buffer("cameraCheck", 16);
    {
        // Kept: the header says so, and the cells start cleared (total 0: no pass reached them yet). Not kept:
        // the traces still bind a buffer, whose header says there is none.
        const uint64_t words = alphaCache ? kAlphaCacheHeaderWords + uint64_t(capacity) * kAlphaCellsPerBrick : kAlphaCacheHeaderWords;
        std::vector<uint32_t> cells(words, 0);
        cells[0] = alphaCache ? 1u : 0u;
        alphaCache_ = buffer(alphaCache ? "alphaCache" : "alphaCacheNone", words * 4, cells.data());
        if (alphaCache) {
            rhi::TextureDesc d;
            d.format = F::D32_FLOAT;
            d.width = d.height = kAlphaPassResolution;
            d.usage = rhi::TextureUsage::DepthTarget;
            d.debugName = desc_.debugName + " alphaPassRaster";
            alphaRaster_ = device_.createTexture(d);
        }
    }

    rhi::SamplerDesc sd;
    sd.minFilter = sd.magFilter = sd.mipFilter = rhi::Filter::Nearest;
    sd.debugName = desc_.debugName + " point";
    point_ = device_.createSampler(sd);
    sd.minFilter = sd.magFilter = rhi::Filter::Linear;
    sd.debugName = desc_.debugName + " linear";
    linear_ = device_.createSampler(sd);
    sd.addressU = rhi::AddressMode::Repeat;
    sd.mipFilter = rhi::Filter::Linear;
    sd.debugName = desc_.debugName + " environment";
    environment_ = device_.createSampler(sd);

    const Shaders& s = shaders_;
    for (rhi::ShaderHandle h : {s.downsample, s.clearFreed, s.inject, s.propagate, s.spawn, s.reprojectProbes, s.fill, s.fillVct,
                                s.pretrace, s.relight, s.reprojectGi, s.specularTrace, s.project, s.emit, s.probeWorld, s.interpolate, s.blur, s.upsample, s.debug, s.cameraCheck,
                                s.reflectionTrace, alphaCache ? s.alphaPass : s.fill})
        if (!h) return bad(ErrorCode::DeviceFailure, "the device could not create the GI shaders (see its messages)");
    bool ok = radianceCache_ && blackCube_ && black2D_ && dummyStorage_ && motion_ && disocclusion_ && pretrace_ && specularTraced_ &&
              probeInfo_[0] && probeInfo_[1] && probeSH_ && probeIrradianceSH_ && probeWorldSH_ && brickSH_ && cacheOwners_ && brickMaterial_ && relightList_[0] && relightList_[1] && lights_ && slotOfBrick_ && freeSlots_ && cameraCheck_.counts && alphaCache_ && (!alphaCache || alphaRaster_) && point_ && linear_ && environment_;
    for (int i = 0; i < 2; ++i)
        ok = ok && depth_[i] && surface_[i] && probes_[i] && diffuseHistory_[i] && specularHistory_[i];
    if (!(desc_.flags & ContextFlags::NoDenoiser)) ok = ok && resolvedDiffuse_ && resolvedSpecular_;
    if (!ok) return bad(ErrorCode::DeviceFailure, "the device could not create the GI resources (see its messages)");
    reset();
    return true;
}

GiContextImpl::~GiContextImpl() {
    const Shaders& s = shaders_;
    for (rhi::ShaderHandle h : {s.downsample, s.clearFreed, s.inject, s.propagate, s.spawn, s.reprojectProbes, s.fill, s.fillVct,
                                s.pretrace, s.relight, s.reprojectGi, s.specularTrace, s.project, s.emit, s.probeWorld, s.interpolate, s.blur, s.upsample, s.debug, s.cameraCheck,
                                s.reflectionTrace, s.alphaPass})
        if (h) device_.destroy(h);
    for (rhi::TextureHandle t : {depth_[0], depth_[1], surface_[0], surface_[1], motion_, disocclusion_, probes_[0], probes_[1], pretrace_,
                                 specularTraced_, diffuseHistory_[0], diffuseHistory_[1], specularHistory_[0], specularHistory_[1],
                                 resolvedDiffuse_, resolvedSpecular_, radianceCache_, blackCube_, black2D_,
                                 dummyStorage_, alphaRaster_})
        if (t) device_.destroy(t);
    for (rhi::BufferHandle b : {probeInfo_[0], probeInfo_[1], probeSH_, probeIrradianceSH_, probeWorldSH_, brickSH_, cacheOwners_, brickMaterial_, relightList_[0], relightList_[1], lights_, slotOfBrick_, freeSlots_, cameraCheck_.counts, alphaCache_})
        if (b) device_.destroy(b);
    for (rhi::SamplerHandle h : {point_, linear_, environment_})
        if (h) device_.destroy(h);
}

void GiContextImpl::reset() {
    rhi::ClearValue zero{};
    device_.clearTexture(radianceCache_, 0, 1, zero);
    device_.clearBuffer(brickSH_, {}, 0);
    device_.clearBuffer(brickMaterial_, {}, 0);
    // Every brick without a slot; the free stack holds all slots, the lowest on top.
    device_.clearBuffer(slotOfBrick_, {}, 0xFFFFFFFFu);
    std::vector<uint32_t> stack(size_t(cacheSlots_) + 1);
    stack[0] = cacheSlots_;
    for (uint32_t i = 0; i < cacheSlots_; ++i) stack[1 + i] = cacheSlots_ - 1 - i;
    device_.writeBuffer(freeSlots_, 0, stack.data(), stack.size() * 4);
    for (rhi::TextureHandle t : {depth_[0], depth_[1], surface_[0], surface_[1], motion_, disocclusion_, probes_[0], probes_[1], pretrace_,
                                 specularTraced_, diffuseHistory_[0], diffuseHistory_[1], specularHistory_[0], specularHistory_[1],
                                 resolvedDiffuse_, resolvedSpecular_, dummyStorage_})
        if (t) device_.clearTexture(t, 0, 1, zero);
    device_.clearBuffer(probeInfo_[0], {}, 0);
    device_.clearBuffer(probeInfo_[1], {}, 0);
    device_.clearBuffer(probeSH_, {}, 0);
    device_.clearBuffer(probeIrradianceSH_, {}, 0);
    device_.clearBuffer(probeWorldSH_, {}, 0);
    for (rhi::BufferHandle b : relightList_) device_.writeBuffer(b, 0, kEmptyRelightList, sizeof(kEmptyRelightList));
    if (desc_.flags & ContextFlags::AlphaCache) {  // cells cleared, the header kept
        device_.clearBuffer(alphaCache_, {kAlphaCacheHeaderWords * 4, 0}, 0);
    }
    historyValid_ = false;
}

MemoryUse GiContextImpl::memoryUse() const {
    MemoryUse m;
    auto add = [&](const char* name, uint64_t bytes) {
        m.resources.push_back({name, bytes});
        m.totalBytes += bytes;
    };
    auto tex = [&](rhi::TextureHandle t) -> uint64_t {
        const rhi::TextureDesc* d = t ? device_.describe(t) : nullptr;
        if (!d) return 0;
        return uint64_t(d->width) * d->height * std::max(1u, d->depthOrLayers) * rhi::formatInfo(d->format).bytesPerTexel;
    };
    auto buf = [&](rhi::BufferHandle b) -> uint64_t {
        const rhi::BufferDesc* d = b ? device_.describe(b) : nullptr;
        return d ? d->size : 0;
    };
    add("radianceCache", tex(radianceCache_));
    add("brickSH", buf(brickSH_));
    add("cacheOwners", buf(cacheOwners_));
    add("cacheSlots", buf(slotOfBrick_) + buf(freeSlots_));
    add("brickMaterial", buf(brickMaterial_));
    if (desc_.flags & ContextFlags::AlphaCache) add("alphaCache", buf(alphaCache_) + tex(alphaRaster_));
    add("relightList (2), lights", buf(relightList_[0]) + buf(relightList_[1]) + buf(lights_));
    add("depth (2)", tex(depth_[0]) + tex(depth_[1]));
    add("surface (2)", tex(surface_[0]) + tex(surface_[1]));
    add("motion", tex(motion_));
    add("disocclusion", tex(disocclusion_));
    add("probes (2)", tex(probes_[0]) + tex(probes_[1]));
    add("probeInfo (2)", buf(probeInfo_[0]) + buf(probeInfo_[1]));
    add("probeSH", buf(probeSH_));
    add("probeIrradianceSH", buf(probeIrradianceSH_));
    add("probeWorldSH", buf(probeWorldSH_));
    add("specularPretrace", tex(pretrace_));
    add("specularTraced", tex(specularTraced_));
    add("diffuseHistory (2)", tex(diffuseHistory_[0]) + tex(diffuseHistory_[1]));
    add("specularHistory (2)", tex(specularHistory_[0]) + tex(specularHistory_[1]));
    add("resolved (2)", tex(resolvedDiffuse_) + tex(resolvedSpecular_));
    add("cameraCheck", buf(cameraCheck_.counts));
    add("environment/dummies", tex(blackCube_) + tex(black2D_) + tex(dummyStorage_));
    return m;
}

void GiContextImpl::readCaches(std::vector<float>* radiance, std::vector<float>* brickSH) {
    if (radiance) {
        std::vector<uint32_t> packed(size_t(64 * kCacheTexelsPerBrick) * 64 * kCacheTexelsPerBrick * cacheDepth_);
        device_.readTexture(radianceCache_, {}, packed.data());
        radiance->resize(packed.size() * 3);
        for (size_t i = 0; i < packed.size(); ++i) {
            const uint32_t v = packed[i];
            const float scale = std::ldexp(1.0f, int(v >> 27) - 24);
            for (int c = 0; c < 3; ++c) (*radiance)[3 * i + size_t(c)] = float((v >> (9 * c)) & 511u) * scale;
        }
    }
    if (brickSH && sceneAlive()) {
        const uint32_t capacity = scene_.brickCapacity();
        std::vector<uint16_t> halves(size_t(capacity) * kShCoefficients * 4);
        device_.readBuffer(brickSH_, 0, halves.size() * 2, halves.data());
        brickSH->assign(size_t(capacity) * 28, 0.0f);
        for (size_t b = 0; b < capacity; ++b) {
            for (size_t k = 0; k < kShCoefficients; ++k)
                for (size_t c = 0; c < 3; ++c) (*brickSH)[b * 28 + 3 * k + c] = halfToFloat(halves[(b * kShCoefficients + k) * 4 + c]);
            (*brickSH)[b * 28 + 27] = halfToFloat(halves[b * kShCoefficients * 4 + 3]);
        }
    }
}

uint64_t GiContextImpl::raysAtAlphaBound() {
    uint32_t count = 0;
    device_.readBuffer(alphaCache_, 8, 4, &count);  // header word 2 (bricklight/alpha_cache.glsl)
    return count;
}

uint32_t GiContextImpl::radianceCacheBricksInUse() {
    int32_t free = 0;
    device_.readBuffer(freeSlots_, 0, 4, &free);
    return cacheSlots_ - uint32_t(std::clamp(free, 0, int32_t(cacheSlots_)));
}

}  // namespace detail
}  // namespace bricklight::gi
