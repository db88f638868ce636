// memoryUse() of the techniques that count their resources from the device (core/common/memory_tally.h): each
// live texture (every mip) and buffer once, named, adding up to the total; exact where the sizes are known.
#include <numeric>

#include "backend_test.h"
#include "bricklight/gbuffer/depth_pyramid.h"
#include "bricklight/reflections/classifier.h"
#include "bricklight/reflections/denoiser.h"
#include "bricklight/shadows/classifier.h"
#include "bricklight/shadows/denoiser.h"
#include "bricklight/vct_scene.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

uint64_t sum(const MemoryUse& use) {
    return std::accumulate(use.resources.begin(), use.resources.end(), uint64_t(0),
                           [](uint64_t s, const MemoryUse::Resource& r) { return s + r.bytes; });
}

// Bytes of the resources whose names start with `prefix`.
uint64_t bytesNamed(const MemoryUse& use, const std::string& prefix) {
    uint64_t bytes = 0;
    for (const MemoryUse::Resource& r : use.resources)
        if (r.name.rfind(prefix, 0) == 0) bytes += r.bytes;
    return bytes;
}

void memoryUseCountsEveryResource(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    constexpr uint32_t w = 64, h = 32;
    Error error;

    auto pyramid = gbuffer::DepthPyramid::create(*td.device, {16, 8}, &error);
    REQUIRE(pyramid);
    // RG32_FLOAT, every mip; and the 32 × 32 texture of six mips bound to the slots a dispatch leaves unused.
    CHECK(pyramid->memoryUse().totalBytes == (16 * 8 + 8 * 4 + 4 * 2 + 2 * 1 + 1 * 1) * 8 + (32 * 32 + 16 * 16 + 8 * 8 + 4 * 4 + 2 * 2 + 1) * 8);

    auto classifier = shadows::ShadowClassifier::create(*td.device, {w, h}, &error);
    REQUIRE(classifier);
    const MemoryUse shadow = classifier->memoryUse();
    CHECK(shadow.totalBytes == sum(shadow));
    CHECK(shadow.resources.size() == 7);  // tile list, two counts, parameters, the no-alpha-cache stand-in, hit and sure masks
    CHECK(shadow.totalBytes >= uint64_t(w / 8) * (h / 4) * (16 + 4 + 4));  // a tile: list entry, hit and sure mask words

    auto shadowDenoiser = shadows::ShadowDenoiser::create(*td.device, {w, h}, &error);
    REQUIRE(shadowDenoiser);
    const MemoryUse denoised = shadowDenoiser->memoryUse();
    CHECK(denoised.totalBytes == sum(denoised));
    CHECK(denoised.resources.size() == 8);  // 2 histories, 2 geometries, 2 filtered, the listed mask, parameters

    auto reflectionClassifier = reflections::ReflectionClassifier::create(*td.device, {w, h}, &error);
    REQUIRE(reflectionClassifier);
    const MemoryUse listed = reflectionClassifier->memoryUse();
    CHECK(listed.totalBytes == sum(listed));
    CHECK(listed.resources.size() == 11);  // three lists, two counts, parameters, two hit counters, tile info and statistics, the no-motion stand-in

    auto reflectionDenoiser = reflections::ReflectionDenoiser::create(*td.device, {w, h}, &error);
    REQUIRE(reflectionDenoiser);
    const MemoryUse reflected = reflectionDenoiser->memoryUse();
    CHECK(reflected.totalBytes == sum(reflected));
    REQUIRE(reflected.resources.size() == 5);
    // Two RGBA16_FLOAT histories and two R32_FLOAT depths; the parameters are the fifth.
    const uint64_t params = reflected.resources.front().bytes;
    CHECK(reflected.totalBytes - params == uint64_t(w) * h * (8 + 4) * 2);

    auto voxels = vct::VoxelScene::create(*td.device, &error);
    REQUIRE(voxels);
    const uint64_t before = voxels->memoryUse().totalBytes;
    const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
    const uint32_t indices[] = {0, 1, 2};
    vct::VoxelMeshArrays a;
    a.positions = positions;
    a.vertexCount = 3;
    a.indices = indices;
    a.indexCount = 3;
    a.name = "triangle";
    const vct::VoxelMeshHandle mesh = voxels->createMesh(a, &error);
    REQUIRE(mesh);
    CHECK(voxels->memoryUse().totalBytes == before + sizeof(positions) + sizeof(indices));  // uploaded from CPU arrays
    CHECK(bytesNamed(voxels->memoryUse(), "voxel scene triangle") == sizeof(positions) + sizeof(indices));
    REQUIRE(voxels->destroyMesh(mesh, &error));
    CHECK(voxels->memoryUse().totalBytes == before);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("memoryUse(): every technique counts each live resource once, adding up to its total", "[gbuffer][quick]",
             memoryUseCountsEveryResource)
