// The rest of the public surface: meshes in the app's own GPU buffers (interleaved f32x3 at a stride
// and offset, f16x4, 16-bit indices at an offset) build exactly the field of the same mesh from CPU
// arrays; the debug view draws every mode; stats arrive without a wait; memory is accounted.
#include <cstring>
#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

// A small closed mesh whose coordinates are exact in half precision (multiples of 1/16).
scenes::TriangleMesh halfExactBox() {
    scenes::TriangleMesh m;
    m.name = "box";
    for (int i = 0; i < 8; ++i)
        m.positions.insert(m.positions.end(), {(i & 1) ? 1.5f : -0.75f, (i & 2) ? 1.25f : -0.5f, (i & 4) ? 0.875f : -1.0f});
    m.indices = {0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5};
    return m;
}

uint16_t toHalf(float f) {  // exact for the values above
    uint32_t x;
    std::memcpy(&x, &f, 4);
    const uint32_t sign = (x >> 16) & 0x8000u;
    const int exponent = int((x >> 23) & 0xFF) - 127 + 15;
    const uint32_t mantissa = (x >> 13) & 0x3FFu;
    if ((x & 0x7FFFFFFFu) == 0) return uint16_t(sign);
    return uint16_t(sign | (uint32_t(exponent) << 10) | mantissa);
}

sdf::SceneDesc smallDesc(TestDevice& td) {
    sdf::SceneDesc d;
    d.cascadeCount = 2;
    d.finestVoxelSize = 0.1f;
    d.atlasBricksPerAxis = 32;
    d.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    return d;
}

void gpuBufferMeshes(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    scenes::TriangleMesh box = halfExactBox();
    const glm::mat4 transform = glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(0.3f, 0.1f, -0.2f)), 0.4f, glm::vec3(0, 1, 0));

    auto fieldOf = [&](auto&& makeMesh) {
        auto scene = sdf::SdfScene::create(dev, smallDesc(td));
        REQUIRE(scene);
        sdf::MeshHandle mesh = makeMesh(*scene);
        REQUIRE(mesh);
        scene->addInstance({mesh, transform});
        sdf::UpdateReport r = scene->update(glm::vec3(0.0f));
        sdf::FieldSnapshot f = scene->readField();
        sdf::Stats st = scene->latestStats();
        UNSCOPED_INFO("update: jobs " << r.jobs << " voxels " << r.voxels << " triangles " << r.trianglesGathered
                      << " deferred " << r.jobsDeferred << "; gpu: processed " << st.trianglesProcessed << " rejected "
                      << st.trianglesRejected << " refs " << st.referencesProcessed << " built " << st.voxelsBuilt
                      << " deferred " << st.voxelsDeferredGpu << " bricks " << st.bricksAllocated);
        return f;
    };
    sdf::FieldSnapshot reference = fieldOf([&](sdf::SdfScene& s) {
        return s.createMesh({box.positions.data(), 8, box.indices.data(), uint32_t(box.indices.size()), "cpu box"});
    });

    // Interleaved: 8 bytes of something, then position, then a normal: stride 24 at offset 8 of the buffer.
    std::vector<float> interleaved(2 + 8 * 6, 7.0f);
    for (int v = 0; v < 8; ++v)
        for (int k = 0; k < 3; ++k) interleaved[2 + size_t(v) * 6 + size_t(k)] = box.positions[size_t(v) * 3 + size_t(k)];
    std::vector<uint16_t> indices16(1 + box.indices.size() + 1, 0);
    for (size_t i = 0; i < box.indices.size(); ++i) indices16[1 + i] = uint16_t(box.indices[i]);
    rhi::BufferHandle vb = dev.createBuffer({interleaved.size() * 4, 0, rhi::BufferUsage::ShaderRead, "interleaved"}, interleaved.data());
    rhi::BufferHandle ib = dev.createBuffer({indices16.size() * 2, 0, rhi::BufferUsage::ShaderRead, "indices16"}, indices16.data());
    sdf::FieldSnapshot strided = fieldOf([&](sdf::SdfScene& s) {
        sdf::MeshBuffers m;
        m.vertexBuffer = vb;
        m.vertexOffset = 8;
        m.vertexStride = 24;
        m.vertexCount = 8;
        m.indexBuffer = ib;
        m.indexOffset = 2;
        m.indexFormat = rhi::IndexFormat::U16;
        m.triangleCount = 12;
        m.boundsMin = glm::vec3(-0.75f, -0.5f, -1.0f);
        m.boundsMax = glm::vec3(1.5f, 1.25f, 0.875f);
        m.name = "strided f32 + u16";
        return s.createMesh(m);
    });
    std::vector<uint16_t> halves;
    for (int v = 0; v < 8; ++v)
        for (int k = 0; k < 4; ++k) halves.push_back(k < 3 ? toHalf(box.positions[size_t(v) * 3 + size_t(k)]) : toHalf(1.0f));
    rhi::BufferHandle hb = dev.createBuffer({halves.size() * 2, 0, rhi::BufferUsage::ShaderRead, "halves"}, halves.data());
    rhi::BufferHandle ib32 = dev.createBuffer({box.indices.size() * 4, 0, rhi::BufferUsage::ShaderRead, "indices32"}, box.indices.data());
    sdf::FieldSnapshot half = fieldOf([&](sdf::SdfScene& s) {
        sdf::MeshBuffers m;
        m.vertexBuffer = hb;
        m.vertexStride = 8;
        m.positionFormat = sdf::PositionFormat::Half4;
        m.vertexCount = 8;
        m.indexBuffer = ib32;
        m.triangleCount = 12;
        m.boundsMin = glm::vec3(-0.75f, -0.5f, -1.0f);
        m.boundsMax = glm::vec3(1.5f, 1.25f, 0.875f);
        m.name = "f16x4 + u32";
        return s.createMesh(m);
    });
    REQUIRE_NO_MESSAGES(td);
    for (const sdf::FieldSnapshot* f : {&strided, &half}) {
        FieldDifference d = compareFields(reference, *f);
        INFO(d.stateMismatches << " state mismatches (" << d.firstMismatch << "), largest brixel difference " << d.maxBrixelDifference);
        CHECK(d.stateMismatches == 0);
        CHECK(d.maxBrixelDifference == 0);
    }
    for (rhi::BufferHandle b : {vb, ib, hb, ib32}) dev.destroy(b);
}

void debugViewAndStats(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    scenes::SceneGeometry cornell = scenes::cornellBox();
    sdf::SceneDesc desc = smallDesc(td);
    desc.finestVoxelSize = 20.0f;
    desc.atlasBricksPerAxis = 32;
    LoadedScene loaded = loadIntoSdf(dev, cornell, desc);
    REQUIRE(loaded.scene);
    sdf::SdfScene& scene = *loaded.scene;
    scene.update(glm::vec3(278, 274, 280));
    // Stats arrive a few frames late without any wait.
    sdf::Stats stats;
    for (int frame = 0; frame < 8 && stats.update == 0; ++frame) {
        dev.endFrame();
        scene.update(glm::vec3(278, 274, 280));
        stats = scene.latestStats();
    }
    INFO("stats: processed " << stats.trianglesProcessed << " rejected " << stats.trianglesRejected << " refs "
                              << stats.referencesProcessed << " bricks " << stats.bricksAllocated << " deferred "
                              << stats.voxelsDeferredGpu);
    CHECK(stats.update == 1);
    CHECK(stats.bricksAllocated > 1000);
    CHECK(stats.bricksUsed + stats.bricksFree == stats.bricksCapacity);
    CHECK(stats.trianglesProcessed == 32);  // the Cornell box's 32 triangles
    CHECK(stats.referencesProcessed > stats.bricksAllocated);
    const sdf::MemoryUse memory = scene.memoryUse();
    CHECK(memory.totalBytes > 256ull * 256 * 256);
    CHECK(memory.resources.front().bytes == 256ull * 256 * 256);

    const uint32_t w = 64, h = 64;
    rhi::TextureDesc td2;
    td2.width = w;
    td2.height = h;
    td2.format = rhi::Format::RGBA8_UNORM;
    td2.usage = rhi::TextureUsage::Storage | rhi::TextureUsage::Sampled;
    td2.debugName = "debug view";
    rhi::TextureHandle image = dev.createTexture(td2);
    const glm::mat4 view = glm::lookAt(glm::vec3(278, 273, -800), glm::vec3(278, 273, 0), glm::vec3(0, 1, 0));
    glm::mat4 projection = glm::perspectiveRH_ZO(glm::radians(39.3f), 1.0f, 10.0f, 5000.0f);
    auto render = [&](sdf::DebugMode mode, bool bounds) {
        sdf::DebugViewDesc d;
        d.view = view;
        d.projection = projection;
        d.output = image;
        d.mode = mode;
        d.showCascadeBounds = bounds;
        d.showInstanceBounds = bounds;
        REQUIRE(scene.debugView(d));
        std::vector<uint8_t> pixels(w * h * 4);
        REQUIRE(dev.readTexture(image, {}, pixels.data()));
        return pixels;
    };
    auto at = [&](const std::vector<uint8_t>& p, uint32_t x, uint32_t y) {
        return glm::ivec3(p[(y * w + x) * 4], p[(y * w + x) * 4 + 1], p[(y * w + x) * 4 + 2]);
    };
    // The camera looks into the box: the back wall (upper left, away from the blocks) faces -z, the floor
    // near the bottom +y.
    std::vector<uint8_t> normals = render(sdf::DebugMode::Normal, false);
    const glm::ivec3 back = at(normals, 20, 20), floor = at(normals, w / 2, h - 4);
    INFO("back wall normal colour " << back.x << "," << back.y << "," << back.z << "; floor " << floor.x << "," << floor.y << "," << floor.z);
    CHECK(std::abs(back.x - 128) < 20);
    CHECK(std::abs(back.y - 128) < 20);
    CHECK(back.z < 20);
    CHECK(floor.y > 235);
    // Every mode draws something that differs from the background, and the overlays change the image.
    size_t hitPixels = 0;
    for (size_t i = 0; i < normals.size(); i += 4) hitPixels += normals[i] != 13 || normals[i + 1] != 13;
    CHECK(hitPixels > w * h / 2);
    std::vector<std::vector<uint8_t>> images;
    for (sdf::DebugMode m : {sdf::DebugMode::Distance, sdf::DebugMode::Iterations, sdf::DebugMode::BrickId,
                             sdf::DebugMode::CascadeId, sdf::DebugMode::Uvw})
        images.push_back(render(m, false));
    for (size_t i = 0; i < images.size(); ++i)
        for (size_t k = i + 1; k < images.size(); ++k) CHECK(images[i] != images[k]);
    std::vector<uint8_t> withBounds = render(sdf::DebugMode::Normal, true);
    size_t changed = 0;
    for (size_t i = 0; i < normals.size(); i += 4) changed += normals[i] != withBounds[i];
    CHECK(changed > 20);
    REQUIRE_NO_MESSAGES(td);
    dev.destroy(image);
}


// The owner entries (SdfScene::brickOwnerBuffer) tell caches keyed by brick id which bricks were freed and
// reallocated: after a rebuild of everything, every allocated brick's entry names the voxel that now maps
// to it, and its allocation generation moved on by one, also where the brick went back to the voxel it
// had (which the GPU's order of atomics decides; the GI kept such a brick's stale light before).
void ownersCountReallocations(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    sdf::SceneDesc desc = smallDesc(td);
    desc.finestVoxelSize = 20.0f;
    LoadedScene loaded = loadIntoSdf(dev, scenes::cornellBox(), desc);
    REQUIRE(loaded.scene);
    sdf::SdfScene& scene = *loaded.scene;
    const glm::vec3 centre(278, 274, 280);
    const uint32_t capacity = scene.brickCapacity();
    auto owners = [&] {
        std::vector<uint32_t> o(capacity);
        REQUIRE(dev.readBuffer(scene.brickOwnerBuffer(), 0, uint64_t(capacity) * 4, o.data()));
        return o;
    };
    scene.update(centre);
    dev.endFrame();
    const sdf::FieldSnapshot before = scene.readField();
    const std::vector<uint32_t> ownersBefore = owners();
    scene.invalidateAll();
    scene.update(centre);
    dev.endFrame();
    const sdf::FieldSnapshot after = scene.readField();
    const std::vector<uint32_t> ownersAfter = owners();
    REQUIRE_NO_MESSAGES(td);
    const uint32_t kNoOwner = 0xFFFFFFFFu;
    uint64_t bricks = 0, sameBrick = 0, wrongVoxel = 0, wrongGeneration = 0;
    for (uint32_t c = 0; c < after.cascades.size(); ++c) {
        for (uint32_t v = 0; v < after.cascades[c].brickMap.size(); ++v) {
            const uint32_t brick = after.cascades[c].brickMap[v];
            if (brick == sdf::FieldSnapshot::kEmpty || brick == sdf::FieldSnapshot::kUnbuilt) continue;
            ++bricks;
            sameBrick += before.cascades[c].brickMap[v] == brick;
            const uint32_t entry = ownersAfter[brick], old = ownersBefore[brick];
            wrongVoxel += (entry >> 24) != c || (entry & 0x3FFFFu) != v;
            const uint32_t expected = old == kNoOwner ? 0u : (((old >> 18) & 63u) + 1u) % 64u;
            wrongGeneration += ((entry >> 18) & 63u) != expected;
        }
    }
    INFO(backend << ": " << bricks << " bricks after the rebuild, " << sameBrick << " of them back in the voxel they had; " << wrongVoxel
                 << " entries name another voxel, " << wrongGeneration << " have the wrong generation");
    CHECK(bricks > 100);
    CHECK(wrongVoxel == 0);
    CHECK(wrongGeneration == 0);
}
}  // namespace

BACKEND_TEST("sdf meshes in the app's GPU buffers build the same field as CPU arrays", "[sdf]", gpuBufferMeshes)
BACKEND_TEST("sdf debug view, stats without waiting, memory", "[sdf]", debugViewAndStats)
BACKEND_TEST("sdf owner entries change whenever a brick is reallocated", "[sdf]", ownersCountReallocations)
