// vct::VoxelScene on both backends: registered meshes (CPU arrays, and the application's interleaved buffers)
// voxelize to exactly the words the application's own draws of the same triangles write; a moved instance
// marks its old and new places dirty, the update rewrites them (equal to a voxelization from scratch) and the
// instances outside are culled; bad meshes, instances and buffers are refused with the object named. The
// compute voxelizer writes the draw path's voxels (big triangles drawn, small and thin ones in compute,
// CPU arrays and the application's buffers, after scrolling and moving), and refuses bad compute materials.
#include <catch2/catch.hpp>

#include <cmath>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "bricklight/vct_scene.h"
#include "test_device.h"
#include "voxelize_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

// The same light (kLightDifferenceBound: none; opacity is compared word for word by the callers).
bool sameLight(VoxelizeHarness& a, VoxelizeHarness& b) {
    const std::vector<float> ea = a.emittance(), eb = b.emittance();
    size_t where = 0;
    const size_t differ = radianceDifferences(ea, eb, a.opacity().size(), kLightDifferenceBound, &where);
    INFO(differ << " light channels differ; the first, " << where << ": " << (differ ? ea[where] : 0.0f) << " vs " << (differ ? eb[where] : 0.0f));
    CHECK(differ == 0);
    return differ == 0;
}

const glm::vec3 kAnchor(16.5f, 16.5f, 16.5f);

vct::ClipmapDesc sceneDesc() {
    vct::ClipmapDesc d;
    d.levels = 2;
    d.resolution = 32;
    d.finestVoxelSize = 1.0f;
    d.emittance = vct::EmittanceMode::Anisotropic;
    return d;
}

// A box as unshared triangles: positions and normals, three per triangle, and indices 0..n−1.
struct BoxArrays {
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
};
BoxArrays boxArrays(const glm::vec3& lo, const glm::vec3& hi) {
    BoxArrays b;
    for (const Triangle& t : boxTriangles(lo, hi))
        for (const glm::vec3& p : t.p) {
            b.positions.insert(b.positions.end(), {p.x, p.y, p.z});
            b.normals.insert(b.normals.end(), {t.normal.x, t.normal.y, t.normal.z});
            b.indices.push_back(uint32_t(b.indices.size()));
        }
    return b;
}

vct::VoxelMeshArrays meshOf(const BoxArrays& b, const char* name) {
    vct::VoxelMeshArrays a;
    a.positions = b.positions.data();
    a.normals = b.normals.data();
    a.vertexCount = uint32_t(b.positions.size() / 3);
    a.indices = b.indices.data();
    a.indexCount = uint32_t(b.indices.size());
    a.name = name;
    return a;
}

std::vector<Triangle> moved(std::vector<Triangle> triangles, const glm::vec3& by) {
    for (Triangle& t : triangles)
        for (glm::vec3& p : t.p) p += by;
    return triangles;
}

// Offsets of whole voxels keep every coordinate exact, so the GPU's transform gives the CPU's positions bit
// for bit and the two paths must write the same words.
void registeredMeshesEqualTheAppsDraws(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const glm::vec3 radiance(0.8f, 0.6f, 0.4f);
    const glm::vec4 emission(radiance, 0.0f);
    Error error;
    auto scene = vct::VoxelScene::create(*td.device, &error);
    INFO(error.message);
    REQUIRE(scene);
    VoxelizeHarness app(td, sceneDesc()), registered(td, sceneDesc());
    vct::VoxelMaterial material, harnessMaterial;  // the harnesses take their own emissive test shader
    material.fragmentShader = app.emissiveShader();
    rhi::Bindings extra;
    extra.constants.push(rhi::constants(0, emission));

    const BoxArrays cube = boxArrays(glm::vec3(3.5f), glm::vec3(11.5f)), far = boxArrays(glm::vec3(24.5f), glm::vec3(28.5f));
    const vct::VoxelMeshHandle cubeMesh = scene->createMesh(meshOf(cube, "cube"), &error), farMesh = scene->createMesh(meshOf(far, "far"), &error);
    REQUIRE(cubeMesh);
    REQUIRE(farMesh);
    vct::VoxelInstanceDesc id;
    id.mesh = cubeMesh;
    id.transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    id.material = material;
    const vct::VoxelInstanceHandle cubeInstance = scene->addInstance(id, &error);
    id.mesh = farMesh;
    id.transform = glm::mat4(1.0f);
    REQUIRE(cubeInstance);
    REQUIRE(scene->addInstance(id, &error));

    REQUIRE(app.clipmap().update(kAnchor, &error));
    app.draw(boxTriangles(glm::vec3(4.5f, 3.5f, 3.5f), glm::vec3(12.5f, 11.5f, 11.5f)), harnessMaterial, &radiance);
    app.draw(boxTriangles(glm::vec3(24.5f), glm::vec3(28.5f)), harnessMaterial, &radiance);
    app.clipmap().finishVoxelization();
    REQUIRE(registered.clipmap().update(kAnchor, &error, scene->takeDirtyRegions()));
    REQUIRE(scene->voxelize(registered.clipmap(), extra, &error));
    CHECK(scene->lastDrawCount() == 2);
    registered.clipmap().finishVoxelization();
    const std::vector<uint32_t> opacity = registered.opacity();
    CHECK(std::count_if(opacity.begin(), opacity.end(), [](uint32_t v) { return v != 0; }) > 100);
    CHECK(opacity == app.opacity());
    CHECK(sameLight(registered, app));

    // The cube moves two voxels: its old and new places are rewritten, the far one is culled, and the result
    // equals a voxelization from scratch.
    REQUIRE(scene->setTransform(cubeInstance, glm::translate(glm::mat4(1.0f), glm::vec3(3.0f, 0.0f, 0.0f)), &error));
    REQUIRE(registered.clipmap().update(kAnchor, &error, scene->takeDirtyRegions()));
    REQUIRE(scene->voxelize(registered.clipmap(), extra, &error));
    CHECK(scene->lastDrawCount() == 1);
    registered.clipmap().finishVoxelization();
    VoxelizeHarness fresh(td, sceneDesc());
    REQUIRE(fresh.clipmap().update(kAnchor, &error));
    fresh.draw(moved(boxTriangles(glm::vec3(3.5f), glm::vec3(11.5f)), glm::vec3(3.0f, 0.0f, 0.0f)), harnessMaterial, &radiance);
    fresh.draw(boxTriangles(glm::vec3(24.5f), glm::vec3(28.5f)), harnessMaterial, &radiance);
    fresh.clipmap().finishVoxelization();
    CHECK(registered.opacity() == fresh.opacity());
    CHECK(sameLight(registered, fresh));

    // The same cube from the application's interleaved buffers (position, normal; stride 24).
    std::vector<float> interleaved;
    for (size_t v = 0; v < cube.positions.size() / 3; ++v)
        for (int c = 0; c < 6; ++c) interleaved.push_back(c < 3 ? cube.positions[3 * v + c] : cube.normals[3 * v + c - 3]);
    rhi::BufferDesc bd;
    bd.size = interleaved.size() * 4;
    bd.usage = rhi::BufferUsage::Vertex;
    bd.debugName = "app vertices";
    const rhi::BufferHandle vertices = td.device->createBuffer(bd, interleaved.data());
    bd.size = cube.indices.size() * 4;
    bd.usage = rhi::BufferUsage::Index;
    bd.debugName = "app indices";
    const rhi::BufferHandle indices = td.device->createBuffer(bd, cube.indices.data());
    vct::VoxelMeshBuffers mb;
    mb.positions = mb.normals = vertices;
    mb.positionsStride = mb.normalsStride = 24;
    mb.normalsOffset = 12;
    mb.vertexCount = uint32_t(cube.positions.size() / 3);
    mb.indices = indices;
    mb.indexCount = uint32_t(cube.indices.size());
    mb.boundsMin = glm::vec3(3.5f);
    mb.boundsMax = glm::vec3(11.5f);
    mb.name = "app cube";
    auto bufferScene = vct::VoxelScene::create(*td.device, &error);
    REQUIRE(bufferScene);
    id.mesh = bufferScene->createMesh(mb, &error);
    INFO(error.message);
    REQUIRE(id.mesh);
    id.transform = glm::translate(glm::mat4(1.0f), glm::vec3(1.0f, 0.0f, 0.0f));
    REQUIRE(bufferScene->addInstance(id, &error));
    VoxelizeHarness fromBuffers(td, sceneDesc()), single(td, sceneDesc());
    REQUIRE(fromBuffers.clipmap().update(kAnchor, &error, bufferScene->takeDirtyRegions()));
    REQUIRE(bufferScene->voxelize(fromBuffers.clipmap(), extra, &error));
    fromBuffers.clipmap().finishVoxelization();
    REQUIRE(single.clipmap().update(kAnchor, &error));
    single.draw(boxTriangles(glm::vec3(4.5f, 3.5f, 3.5f), glm::vec3(12.5f, 11.5f, 11.5f)), harnessMaterial, &radiance);
    single.clipmap().finishVoxelization();
    CHECK(fromBuffers.opacity() == single.opacity());
    CHECK(sameLight(fromBuffers, single));
    bufferScene.reset();
    td.device->destroy(vertices);
    td.device->destroy(indices);
    REQUIRE_NO_MESSAGES(td);
}

void refusesBadMeshesAndInstances(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    Error error;
    auto scene = vct::VoxelScene::create(*td.device, &error);
    REQUIRE(scene);
    BoxArrays cube = boxArrays(glm::vec3(1.0f), glm::vec3(2.0f));
    cube.positions[4] = NAN;
    CHECK_FALSE(scene->createMesh(meshOf(cube, "broken"), &error));
    CHECK(error.message.find("mesh 'broken'") != std::string::npos);
    CHECK(error.message.find("vertex 1") != std::string::npos);
    cube = boxArrays(glm::vec3(1.0f), glm::vec3(2.0f));
    cube.indices[7] = 1000;
    CHECK_FALSE(scene->createMesh(meshOf(cube, "indices"), &error));
    CHECK(error.message.find("index 7 is 1000") != std::string::npos);
    cube = boxArrays(glm::vec3(1.0f), glm::vec3(2.0f));
    vct::VoxelMeshArrays a = meshOf(cube, "short");
    a.indexCount = 4;
    CHECK_FALSE(scene->createMesh(a, &error));
    CHECK(error.message.find("multiple of 3") != std::string::npos);

    rhi::BufferDesc bd;
    bd.size = 64;
    bd.usage = rhi::BufferUsage::Vertex;
    bd.debugName = "tiny";
    const rhi::BufferHandle tiny = td.device->createBuffer(bd);
    vct::VoxelMeshBuffers mb;
    mb.positions = tiny;
    mb.vertexCount = 36;
    mb.indices = tiny;
    mb.indexCount = 36;
    mb.name = "too small";
    CHECK_FALSE(scene->createMesh(mb, &error));
    CHECK(error.message.find("positions needs 432 bytes") != std::string::npos);
    mb.vertexCount = 4;
    CHECK_FALSE(scene->createMesh(mb, &error));
    CHECK(error.message.find("indices lacks the Index usage") != std::string::npos);
    td.device->destroy(tiny);

    const vct::VoxelMeshHandle mesh = scene->createMesh(meshOf(cube, "good"), &error);
    REQUIRE(mesh);
    vct::VoxelInstanceDesc id;
    id.mesh = vct::VoxelMeshHandle{999};
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.message.find("unknown mesh 999") != std::string::npos);
    id.mesh = mesh;
    id.transform = glm::mat4(0.0f);
    id.transform[3][3] = 1.0f;
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.message.find("invertible") != std::string::npos);
    id.transform = glm::mat4(1.0f);
    id.material.opacity = 2.0f;
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.message.find("opacity") != std::string::npos);
    id.material.opacity = 1.0f;
    const vct::VoxelInstanceHandle instance = scene->addInstance(id, &error);
    REQUIRE(instance);
    CHECK_FALSE(scene->setTransform(instance, glm::mat4(NAN), &error));
    CHECK_FALSE(scene->destroyMesh(mesh, &error));
    CHECK(error.message.find("used by 1 instance") != std::string::npos);
    CHECK(scene->removeInstance(instance, &error));
    CHECK(scene->destroyMesh(mesh, &error));
    CHECK(scene->takeDirtyRegions().size() == 2);  // where the instance was added and removed (refusals mark nothing)
    REQUIRE_NO_MESSAGES(td);
}

// Triangle lists as mesh arrays, with per-vertex normals or without (each triangle's own normal then).
struct MeshArrays {
    std::vector<float> positions, normals;
    std::vector<uint32_t> indices;
    void add(const glm::vec3 (&p)[3], const glm::vec3* n) {
        for (int k = 0; k < 3; ++k) {
            indices.push_back(uint32_t(positions.size() / 3));
            positions.insert(positions.end(), {p[k].x, p[k].y, p[k].z});
            if (n) normals.insert(normals.end(), {n[k].x, n[k].y, n[k].z});
        }
    }
    vct::VoxelMeshArrays arrays(const char* name) const {
        vct::VoxelMeshArrays a;
        a.positions = positions.data();
        a.normals = normals.empty() ? nullptr : normals.data();
        a.vertexCount = uint32_t(positions.size() / 3);
        a.indices = indices.data();
        a.indexCount = uint32_t(indices.size());
        a.name = name;
        return a;
    }
};

// Small triangles with smooth normals (a sphere of ~1-voxel facets) in one mesh with two big ones (a floor
// across both levels), so that the compute voxelizer splits the mesh.
MeshArrays sphereAndFloor() {
    MeshArrays m;
    const glm::vec3 centre(14.3f, 17.6f, 15.2f);
    const float radius = 4.7f;
    const int slices = 20, stacks = 12;
    auto at = [&](int i, int j) {
        const float theta = 3.14159265f * float(j) / float(stacks), phi = 6.2831853f * float(i) / float(slices);
        return glm::vec3(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
    };
    for (int j = 0; j < stacks; ++j)
        for (int i = 0; i < slices; ++i) {
            const glm::vec3 n[4] = {at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)};
            const glm::vec3 a[3] = {centre + radius * n[0], centre + radius * n[1], centre + radius * n[2]};
            const glm::vec3 na[3] = {n[0], n[1], n[2]};
            const glm::vec3 b[3] = {centre + radius * n[0], centre + radius * n[2], centre + radius * n[3]};
            const glm::vec3 nb[3] = {n[0], n[2], n[3]};
            m.add(a, na);
            m.add(b, nb);
        }
    const glm::vec3 up[3] = {glm::vec3(0, 1, 0), glm::vec3(0, 1, 0), glm::vec3(0, 1, 0)};
    const glm::vec3 f0[3] = {{-30.0f, 6.25f, -30.0f}, {60.0f, 6.25f, 60.0f}, {60.0f, 6.25f, -30.0f}};
    const glm::vec3 f1[3] = {{-30.0f, 6.25f, -30.0f}, {-30.0f, 6.25f, 60.0f}, {60.0f, 6.25f, 60.0f}};
    m.add(f0, up);
    m.add(f1, up);
    return m;
}

// Thin slivers along every axis, tiny triangles, one degenerate and one on voxel boundaries; no normals.
MeshArrays slivers() {
    MeshArrays m;
    for (int i = 0; i < 24; ++i) {
        const glm::vec3 a(2.3f + 1.1f * float(i), 3.3f + 0.37f * float(i % 5), 22.1f + 0.21f * float(i % 7));
        const glm::vec3 along = i % 3 == 0 ? glm::vec3(3.7f, 0.013f * float(i), 0.4f) : i % 3 == 1 ? glm::vec3(0.05f, 3.1f, 0.02f) : glm::vec3(0.3f, 0.01f, 3.3f);
        const glm::vec3 t[3] = {a, a + along, a + glm::vec3(0.02f, 0.03f, 0.001f * float(i))};
        m.add(t, nullptr);
        const glm::vec3 tiny[3] = {a + glm::vec3(0.0f, 1.5f, 0.0f), a + glm::vec3(0.1f, 1.52f, 0.03f), a + glm::vec3(0.02f, 1.6f, 0.07f)};
        m.add(tiny, nullptr);
    }
    const glm::vec3 degenerate[3] = {{5.0f, 5.0f, 5.0f}, {6.0f, 6.0f, 6.0f}, {7.0f, 7.0f, 7.0f}};
    const glm::vec3 aligned[3] = {{8.0f, 9.0f, 10.0f}, {10.0f, 9.0f, 10.0f}, {8.0f, 9.0f, 12.0f}};
    m.add(degenerate, nullptr);
    m.add(aligned, nullptr);
    return m;
}

// How many words differ, and where the first few lie (index: what a long vector's print would not show).
size_t differences(const std::vector<uint32_t>& a, const std::vector<uint32_t>& b, std::string* where) {
    if (a.size() != b.size()) {
        *where = "sizes " + std::to_string(a.size()) + " vs " + std::to_string(b.size());
        return std::max(a.size(), b.size());
    }
    size_t count = 0;
    for (size_t i = 0; i < a.size(); ++i)
        if (a[i] != b[i] && count++ < 8) *where += "word " + std::to_string(i) + ": " + std::to_string(a[i]) + " vs " + std::to_string(b[i]) + "; ";
    return count;
}

// One scene, its clip-map and counters: the same meshes and instances in each, voxelized in one way.
struct Voxelization {
    std::unique_ptr<VoxelizeHarness> harness;
    std::unique_ptr<vct::VoxelScene> scene;
    std::vector<vct::VoxelInstanceHandle> instances;
    vct::VoxelizationCounters counters;
    uint32_t drawn = 0, computed = 0;
};

void computeVoxelizerWritesTheDrawPathsWords(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const glm::vec4 emission(0.8f, 0.6f, 0.4f, 0.0f);
    rhi::Bindings extra;
    extra.constants.push(rhi::constants(0, emission));
    Error error;
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct_tests/voxelize_emissive.comp");
    REQUIRE(sd.blob);
    const rhi::ShaderHandle emissiveCompute = td.device->createShader(sd);
    REQUIRE(emissiveCompute);

    const MeshArrays mixed = sphereAndFloor(), thin = slivers();
    const BoxArrays cube = boxArrays(glm::vec3(3.5f), glm::vec3(11.5f));
    // The cube from the application's interleaved buffers, once readable by compute (ShaderRead) and once not.
    std::vector<float> interleaved;
    for (size_t v = 0; v < cube.positions.size() / 3; ++v)
        for (int c = 0; c < 6; ++c) interleaved.push_back(c < 3 ? cube.positions[3 * v + c] : cube.normals[3 * v + c - 3]);
    rhi::BufferHandle appBuffers[4];
    for (int readable = 0; readable < 2; ++readable) {
        rhi::BufferDesc bd;
        bd.size = interleaved.size() * 4;
        bd.usage = rhi::BufferUsage::Vertex | (readable ? rhi::BufferUsage::ShaderRead : 0u);
        bd.debugName = readable ? "app vertices (readable)" : "app vertices";
        appBuffers[2 * readable] = td.device->createBuffer(bd, interleaved.data());
        bd.size = cube.indices.size() * 4;
        bd.usage = rhi::BufferUsage::Index | (readable ? rhi::BufferUsage::ShaderRead : 0u);
        bd.debugName = readable ? "app indices (readable)" : "app indices";
        appBuffers[2 * readable + 1] = td.device->createBuffer(bd, cube.indices.data());
    }

    // Draws; compute with the default split, every triangle drawn, none drawn (a floor of ~90² voxels in one
    // invocation per level).
    std::vector<Voxelization> runs(4);
    const vct::ComputeVoxelizer options[4] = {{}, {}, {0.0f}, {1.0e6f}};
    for (size_t r = 0; r < runs.size(); ++r) {
        Voxelization& v = runs[r];
        v.harness = std::make_unique<VoxelizeHarness>(td, sceneDesc());
        v.scene = vct::VoxelScene::create(*td.device, &error);
        REQUIRE(v.scene);
        if (r > 0) v.scene->setVoxelizer(vct::Voxelizer::Compute, options[r]);
        vct::VoxelMaterial emissive, fragmentOnly, opaque;
        emissive.fragmentShader = fragmentOnly.fragmentShader = v.harness->emissiveShader();
        emissive.computeShader = emissiveCompute;
        opaque.thickness = 0.5f;
        opaque.twoSided = true;
        auto instance = [&](vct::VoxelMeshHandle mesh, const glm::vec3& at, const vct::VoxelMaterial& material) {
            INFO(error.message);
            REQUIRE(mesh);
            vct::VoxelInstanceDesc id;
            id.mesh = mesh;
            id.transform = glm::translate(glm::mat4(1.0f), at);
            id.material = material;
            v.instances.push_back(v.scene->addInstance(id, &error));
            REQUIRE(v.instances.back());
        };
        instance(v.scene->createMesh(mixed.arrays("sphere and floor"), &error), glm::vec3(0.25f, 0.0f, -0.5f), emissive);
        instance(v.scene->createMesh(thin.arrays("slivers"), &error), glm::vec3(0.0f), opaque);
        for (int readable = 0; readable < 2; ++readable) {
            vct::VoxelMeshBuffers mb;
            mb.positions = mb.normals = appBuffers[2 * readable];
            mb.positionsStride = mb.normalsStride = 24;
            mb.normalsOffset = 12;
            mb.vertexCount = uint32_t(cube.positions.size() / 3);
            mb.indices = appBuffers[2 * readable + 1];
            mb.indexCount = uint32_t(cube.indices.size());
            mb.boundsMin = glm::vec3(3.5f);
            mb.boundsMax = glm::vec3(11.5f);
            mb.name = readable ? "app cube (readable)" : "app cube";
            instance(v.scene->createMesh(mb, &error), readable ? glm::vec3(14.0f, 1.0f, 0.0f) : glm::vec3(0.0f, 14.0f, 12.0f), emissive);
        }
        // An emissive material without a compute shader: drawn, whatever the voxelizer.
        instance(v.scene->createMesh(meshOf(cube, "cube"), &error), glm::vec3(-20.0f, 2.0f, 18.0f),
                 fragmentOnly);
    }
    auto voxelize = [&](const glm::vec3& anchor) {
        for (Voxelization& v : runs) {
            vct::Clipmap& clipmap = v.harness->clipmap();
            clipmap.setCountersEnabled(true);
            clipmap.resetCounters();
            REQUIRE(clipmap.update(anchor, &error, v.scene->takeDirtyRegions()));
            const bool voxelized = v.scene->voxelize(clipmap, extra, &error);
            INFO(error.message);
            REQUIRE(voxelized);
            v.drawn = v.scene->lastDrawCount();
            v.computed = v.scene->lastComputeCount();
            clipmap.finishVoxelization();
            v.counters = clipmap.readCounters();
        }
        const std::vector<uint32_t> opacity = runs[0].harness->opacity();
        const std::vector<float> emittance = runs[0].harness->emittance();
        CHECK(std::count_if(opacity.begin(), opacity.end(), [](uint32_t w) { return w != 0; }) > 1000);
        CHECK(std::count_if(emittance.begin(), emittance.end(), [](float w) { return w != 0.0f; }) > 1000);
        CHECK(runs[0].computed == 0);
        for (size_t r = 1; r < runs.size(); ++r) {
            INFO("compute run " << r << " (split " << options[r].splitVoxels << ")");
            std::string where;
            CHECK(differences(runs[r].harness->opacity(), opacity, &where) == 0);
            CHECK(sameLight(*runs[r].harness, *runs[0].harness));
            INFO(where);
            CHECK(where.empty());
            CHECK(runs[r].drawn == runs[0].drawn);
            // Fragments differ (the compute loop visits only the pixels of the triangle's bounding box); the
            // writes do not.
            CHECK(runs[r].counters.voxelsWritten == runs[0].counters.voxelsWritten);
            CHECK(runs[r].counters.killedByFiner == runs[0].counters.killedByFiner);
            CHECK(runs[r].counters.killedNotDirty == runs[0].counters.killedNotDirty);
            CHECK(runs[r].counters.emittanceWrites == runs[0].counters.emittanceWrites);
        }
    };
    voxelize(kAnchor);
    CHECK(runs[0].drawn == 5);
    CHECK(runs[1].computed == 3);  // the sphere, the slivers and the readable app cube; not the other two
    CHECK(runs[1].counters.voxelsWritten > 1000);

    // Persistent: the clip-map scrolls and the slivers move; only what meets the rewrite regions is voxelized.
    for (Voxelization& v : runs) REQUIRE(v.scene->setTransform(v.instances[1], glm::translate(glm::mat4(1.0f), glm::vec3(2.0f, 1.0f, 0.0f)), &error));
    voxelize(kAnchor + glm::vec3(5.0f, 0.0f, -3.0f));
    CHECK(runs[0].drawn < 5);
    voxelize(kAnchor + glm::vec3(5.0f, 2.0f, -3.0f));

    runs.clear();
    for (rhi::BufferHandle b : appBuffers) td.device->destroy(b);
    td.device->destroy(emissiveCompute);
    REQUIRE_NO_MESSAGES(td);
}

void computeVoxelizerRefusesBadMaterials(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    Error error;
    const glm::vec4 emission(1.0f, 0.5f, 0.25f, 0.0f);
    rhi::Bindings extra;
    extra.constants.push(rhi::constants(0, emission));
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct_tests/voxelize_emissive.comp");
    REQUIRE(sd.blob);
    const rhi::ShaderHandle emissiveCompute = td.device->createShader(sd);
    REQUIRE(emissiveCompute);
    VoxelizeHarness computed(td, sceneDesc()), drawn(td, sceneDesc());
    auto scene = vct::VoxelScene::create(*td.device, &error);
    REQUIRE(scene);
    const BoxArrays cube = boxArrays(glm::vec3(3.25f), glm::vec3(6.5f));  // triangles of ~3 voxels: in compute
    const vct::VoxelMeshHandle mesh = scene->createMesh(meshOf(cube, "cube"), &error);
    REQUIRE(mesh);
    vct::VoxelInstanceDesc id;
    id.mesh = mesh;
    id.material.computeShader = emissiveCompute;  // without its fragment shader: the big triangles would lose light
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.message.find("mesh 'cube'") != std::string::npos);
    CHECK(error.message.find("computeShader but no fragmentShader") != std::string::npos);

    // A fragment shader given as the compute shader: the dispatch is refused, the error names the instance, and
    // the instance is drawn instead (the same words as the draw path).
    id.material.fragmentShader = computed.emissiveShader();
    id.material.computeShader = computed.emissiveShader();
    REQUIRE(scene->addInstance(id, &error));
    scene->setVoxelizer(vct::Voxelizer::Compute);
    REQUIRE(computed.clipmap().update(kAnchor, &error, scene->takeDirtyRegions()));
    CHECK_FALSE(scene->voxelize(computed.clipmap(), extra, &error));
    CHECK(error.message.find("mesh 'cube'") != std::string::npos);
    CHECK(error.message.find("refused the compute voxelizer's dispatch") != std::string::npos);
    CHECK(error.message.find("drawn instead") != std::string::npos);
    CHECK(scene->lastDrawCount() == 1);
    CHECK(scene->lastComputeCount() == 0);
    computed.clipmap().finishVoxelization();
    const bool named = std::any_of(td.messages->begin(), td.messages->end(),
                                   [](const std::string& m) { return m.find("not a compute shader") != std::string::npos; });
    CHECK(named);
    td.messages->clear();
    REQUIRE(drawn.clipmap().update(kAnchor, &error));
    vct::VoxelMaterial harnessMaterial;
    const glm::vec3 radiance(emission);
    drawn.draw(boxTriangles(glm::vec3(3.25f), glm::vec3(6.5f)), harnessMaterial, &radiance);
    drawn.clipmap().finishVoxelization();
    CHECK(computed.opacity() == drawn.opacity());
    CHECK(sameLight(computed, drawn));
    scene.reset();
    td.device->destroy(emissiveCompute);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("registered meshes voxelize as the application's own draws do", "[vct]", registeredMeshesEqualTheAppsDraws)
BACKEND_TEST("a voxel scene refuses bad meshes, buffers and instances", "[vct]", refusesBadMeshesAndInstances)
BACKEND_TEST("the compute voxelizer writes the draw path's words", "[vct]", computeVoxelizerWritesTheDrawPathsWords)
BACKEND_TEST("the compute voxelizer refuses bad materials", "[vct]", computeVoxelizerRefusesBadMaterials)
