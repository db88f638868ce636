// vct::Clipmap on both backends: the clears of the voxels an update rewrites (what entered a level, what left the
// finer level inside it) land in the atlas's opacity region where the CPU placement says (the GLSL addressing in
// include/bricklight/vct_layout.glsl equals ClipmapPlacement::toroidalTexel), and nothing else is touched.
#include <catch2/catch.hpp>

#include <memory>
#include <vector>

#include "backend_test.h"
#include "bricklight/vct.h"
#include "test_device.h"

using namespace bricklight;
using bricklight::testing::makeDevice;
using bricklight::testing::TestDevice;

namespace {

constexpr uint32_t kResolution = 32, kLevels = 2, kMarker = 7;

// The clip-map's atlas, every word (bricklight/vct_layout.glsl): 7 regions (opacity, six directions).
constexpr uint32_t kRegions = 7, kWidth = kRegions * (kResolution + 2);

std::vector<uint32_t> readVolume(TestDevice& td, rhi::TextureHandle atlas) {
    const rhi::TextureDesc* d = td.device->describe(atlas);
    REQUIRE(d);
    REQUIRE(d->width == kWidth);
    std::vector<uint32_t> texels(size_t(d->width) * d->height * d->depthOrLayers);
    REQUIRE(td.device->readTexture(atlas, {}, texels.data()));
    return texels;
}

uint32_t texelOf(const std::vector<uint32_t>& texels, const vct::ClipmapPlacement& p, uint32_t region, uint32_t level, glm::ivec3 voxel) {
    const glm::ivec3 t = p.toroidalTexel(voxel) + glm::ivec3(int(region * (kResolution + 2)) + 1, 0, int(level * (kResolution + 2)) + 1);
    return texels[(size_t(t.z) * kResolution + size_t(t.y)) * kWidth + size_t(t.x)];
}

void clearsWhatEntered(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc;
    desc.levels = kLevels;
    desc.resolution = kResolution;
    desc.finestVoxelSize = 0.25f;
    Error error;
    auto clipmap = vct::Clipmap::create(*td.device, desc, &error);
    INFO(error.message);
    REQUIRE(clipmap);
    CHECK(clipmap->memoryUse().totalBytes == vct::clipmapBytes(desc));
    // The first update clears every level whole.
    rhi::ClearValue marker{};
    marker.u[0] = kMarker;
    REQUIRE(td.device->clearTexture(clipmap->atlas(), 0, 1, marker));
    REQUIRE(clipmap->update(glm::vec3(1.1f, -0.4f, 2.0f), &error));
    {
        // Every level's opacity voxels (the borders and the mips' slab are rewritten by finishVoxelization, not
        // cleared; the direction regions are overwritten by its resolve).
        const std::vector<uint32_t> texels = readVolume(td, clipmap->atlas());
        const vct::ClipmapPlacement& p = clipmap->placement();
        for (uint32_t region = 0; region < 1; ++region)
            for (uint32_t level = 0; level < kLevels; ++level)
                for (int z = 0; z < int(kResolution); ++z)
                    for (int y = 0; y < int(kResolution); ++y)
                        for (int x = 0; x < int(kResolution); ++x) REQUIRE(texelOf(texels, p, region, level, p.origin(level) + glm::ivec3(x, y, z)) == 0u);
    }
    // Then only what entered: mark everything, move (a slab on x and y, across negative coordinates), read.
    REQUIRE(td.device->clearTexture(clipmap->atlas(), 0, 1, marker));
    auto updates = clipmap->update(glm::vec3(-1.3f, 0.9f, 2.0f), &error);
    REQUIRE(updates);
    const std::vector<uint32_t> texels = readVolume(td, clipmap->atlas());
    const vct::ClipmapPlacement& p = clipmap->placement();
    uint64_t cleared = 0, entered = 0, rewritten = 0;
    for (const vct::LevelUpdate& u : *updates) {
        for (const vct::VoxelBox& b : u.entered) entered += b.voxelCount();
        const glm::ivec3 o = p.origin(u.level);
        for (int z = o.z; z < o.z + int(kResolution); ++z)
            for (int y = o.y; y < o.y + int(kResolution); ++y)
                for (int x = o.x; x < o.x + int(kResolution); ++x) {
                    bool inEntered = false;  // what entered the level, or left the finer level inside it
                    for (const vct::LevelBox& lb : clipmap->rewriteBoxes()) {
                        const vct::VoxelBox& b = lb.box;
                        inEntered = inEntered || (lb.level == u.level && x >= b.min.x && y >= b.min.y && z >= b.min.z &&
                                                  x < b.max.x && y < b.max.y && z < b.max.z);
                    }
                    rewritten += inEntered;
                    // The opacity region cleared where the update rewrites; the direction regions untouched.
                    for (uint32_t region = 0; region < kRegions; ++region) {
                        const uint32_t value = texelOf(texels, p, region, u.level, {x, y, z});
                        const uint32_t expected = region == 0 && inEntered ? 0u : kMarker;
                        if (value == 0u && region == 0) ++cleared;
                        if (value != expected) {
                            INFO("region " << region << " level " << u.level << " voxel (" << x << ", " << y << ", " << z << ")");
                            REQUIRE(value == expected);
                        }
                    }
                }
    }
    INFO("entered voxels " << entered);
    CHECK(entered > 0);
    CHECK(rewritten >= entered);
    CHECK(cleared == rewritten);
    // A refused anchor records nothing.
    REQUIRE(td.device->clearTexture(clipmap->atlas(), 0, 1, marker));
    CHECK_FALSE(clipmap->update(glm::vec3(INFINITY, 0.0f, 0.0f), &error));
    CHECK(error.message.find("anchor") != std::string::npos);
    for (uint32_t v : readVolume(td, clipmap->atlas())) REQUIRE(v == kMarker);
    REQUIRE_NO_MESSAGES(td);
}

void refusesBadDescriptions(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc;
    desc.resolution = 48;
    Error error;
    CHECK_FALSE(vct::Clipmap::create(*td.device, desc, &error));
    CHECK(error.message.find("resolution 48") != std::string::npos);
    REQUIRE_NO_MESSAGES(td);
}

// A clip-map of kLevels × kResolution³ (six-direction emittance unless told) for the cone tracer's refusals.
std::unique_ptr<vct::Clipmap> smallClipmap(TestDevice& td, vct::EmittanceMode emittance = vct::ClipmapDesc{}.emittance) {
    vct::ClipmapDesc desc;
    desc.levels = kLevels;
    desc.resolution = kResolution;
    desc.emittance = emittance;
    Error error;
    auto clipmap = vct::Clipmap::create(*td.device, desc, &error);
    INFO(error.message);
    REQUIRE(clipmap);
    return clipmap;
}

void coneSamplesRefuseBadRequests(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto clipmap = smallClipmap(td);
    Error error;
    auto tracer = vct::ConeTracer::create(*td.device, *clipmap, {16, 16}, &error);
    REQUIRE(tracer);
    rhi::TextureDesc od;
    od.width = od.height = 16;
    od.format = rhi::Format::RGBA8_UNORM;
    od.usage = rhi::TextureUsage::Storage;
    const rhi::TextureHandle output = td.device->createTexture(od);
    CHECK_FALSE(tracer->debugConeSamples(0, 0, output, &error));
    CHECK(error.message.find("nothing traced yet") != std::string::npos);
    CHECK(tracer->readConeSamples().empty());
    td.device->destroy(output);
    REQUIRE_NO_MESSAGES(td);
}

// The shaders hold the refinement's room as a float: past 2^24 entries it would round, so it is refused.
void coneTracerRefusesTooLargeARefinement(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto clipmap = smallClipmap(td);
    Error error;
    CHECK_FALSE(vct::ConeTracer::create(*td.device, *clipmap, {16, 16, (1u << 24) + 1u}, &error));
    CHECK(error.message.find("refinementEntries 16777217") != std::string::npos);
    CHECK(vct::ConeTracer::create(*td.device, *clipmap, {16, 16, 0}, &error));
    REQUIRE_NO_MESSAGES(td);
}

// A clip-map without emittance (voxel AO) holds no light for a specular cone: a specular output is refused with the
// output named (a black image would be silently wrong), and such a tracer allocates no specular history.
void coneTracerRefusesSpecularWithoutEmittance(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    auto clipmap = smallClipmap(td, vct::EmittanceMode::None);
    Error error;
    auto tracer = vct::ConeTracer::create(*td.device, *clipmap, {16, 16}, &error);
    INFO(error.message);
    REQUIRE(tracer);
    for (const MemoryUse::Resource& r : tracer->memoryUse().resources) CHECK(r.name.find("specular") == std::string::npos);
    rhi::TextureDesc desc;
    desc.width = desc.height = 16;
    desc.usage = rhi::TextureUsage::Sampled;
    desc.format = rhi::Format::R32_FLOAT;
    const rhi::TextureHandle depth = td.device->createTexture(desc);
    desc.format = rhi::Format::RGBA16_FLOAT;
    const rhi::TextureHandle normals = td.device->createTexture(desc);
    desc.usage = rhi::TextureUsage::Sampled | rhi::TextureUsage::Storage;
    const rhi::TextureHandle diffuse = td.device->createTexture(desc), specular = td.device->createTexture(desc);
    vct::TraceDesc d;
    d.gbuffer.depth = depth;
    d.gbuffer.normals = d.gbuffer.roughness = normals;
    d.outputDiffuse = diffuse;
    d.outputSpecular = specular;
    CHECK_FALSE(tracer->dispatch(d, &error));
    CHECK(error.message.find("outputSpecular needs a clip-map with emittance") != std::string::npos);
    CHECK(error.code == ErrorCode::Unsupported);
    for (rhi::TextureHandle t : {depth, normals, diffuse, specular}) td.device->destroy(t);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("the cone tracer refuses a specular output from a clip-map without emittance", "[vct]", coneTracerRefusesSpecularWithoutEmittance)
BACKEND_TEST("the cone tracer's sample record refuses requests before any trace", "[vct]", coneSamplesRefuseBadRequests)
BACKEND_TEST("the cone tracer refuses a refinement room past 2^24 entries", "[vct]", coneTracerRefusesTooLargeARefinement)
BACKEND_TEST("clip-map clears exactly the voxels that entered its levels", "[vct]", clearsWhatEntered)
BACKEND_TEST("clip-map refuses a bad description", "[vct]", refusesBadDescriptions)
