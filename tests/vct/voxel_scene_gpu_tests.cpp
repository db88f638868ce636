// vct::VoxelScene on both backends: registered meshes (CPU arrays, and the application's interleaved buffers)
// voxelize to exactly the words the application's own draws of the same triangles write; a moved instance
// marks its old and new places dirty, the update rewrites them (equal to a voxelization from scratch) and the
// instances outside are culled; bad meshes, instances and buffers are refused with the object named.
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
    std::string error;
    auto scene = vct::VoxelScene::create(*td.device, &error);
    INFO(error);
    REQUIRE(scene);
    VoxelizeHarness app(td, sceneDesc()), registered(td, sceneDesc());
    vct::VoxelMaterial material, harnessMaterial;  // the harnesses take their own emissive test shader
    material.fragmentShader = app.emissiveShader();
    rhi::Bindings extra;
    extra.constants.push(rhi::constants(0, emission));

    const BoxArrays cube = boxArrays(glm::vec3(3.5f), glm::vec3(11.5f)), far = boxArrays(glm::vec3(24.5f), glm::vec3(28.5f));
    const vct::VoxelMeshHandle cubeMesh = scene->addMesh(meshOf(cube, "cube"), &error), farMesh = scene->addMesh(meshOf(far, "far"), &error);
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
    CHECK(registered.emittance() == app.emittance());

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
    CHECK(registered.emittance() == fresh.emittance());

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
    id.mesh = bufferScene->addMesh(mb, &error);
    INFO(error);
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
    CHECK(fromBuffers.emittance() == single.emittance());
    bufferScene.reset();
    td.device->destroy(vertices);
    td.device->destroy(indices);
    REQUIRE_NO_MESSAGES(td);
}

void refusesBadMeshesAndInstances(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    std::string error;
    auto scene = vct::VoxelScene::create(*td.device, &error);
    REQUIRE(scene);
    BoxArrays cube = boxArrays(glm::vec3(1.0f), glm::vec3(2.0f));
    cube.positions[4] = NAN;
    CHECK_FALSE(scene->addMesh(meshOf(cube, "broken"), &error));
    CHECK(error.find("mesh 'broken'") != std::string::npos);
    CHECK(error.find("vertex 1") != std::string::npos);
    cube = boxArrays(glm::vec3(1.0f), glm::vec3(2.0f));
    cube.indices[7] = 1000;
    CHECK_FALSE(scene->addMesh(meshOf(cube, "indices"), &error));
    CHECK(error.find("index 7 is 1000") != std::string::npos);
    cube = boxArrays(glm::vec3(1.0f), glm::vec3(2.0f));
    vct::VoxelMeshArrays a = meshOf(cube, "short");
    a.indexCount = 4;
    CHECK_FALSE(scene->addMesh(a, &error));
    CHECK(error.find("multiple of 3") != std::string::npos);

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
    CHECK_FALSE(scene->addMesh(mb, &error));
    CHECK(error.find("positions needs 432 bytes") != std::string::npos);
    mb.vertexCount = 4;
    CHECK_FALSE(scene->addMesh(mb, &error));
    CHECK(error.find("indices lacks the Index usage") != std::string::npos);
    td.device->destroy(tiny);

    const vct::VoxelMeshHandle mesh = scene->addMesh(meshOf(cube, "good"), &error);
    REQUIRE(mesh);
    vct::VoxelInstanceDesc id;
    id.mesh = vct::VoxelMeshHandle{999};
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.find("unknown mesh 999") != std::string::npos);
    id.mesh = mesh;
    id.transform = glm::mat4(0.0f);
    id.transform[3][3] = 1.0f;
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.find("invertible") != std::string::npos);
    id.transform = glm::mat4(1.0f);
    id.material.opacity = 2.0f;
    CHECK_FALSE(scene->addInstance(id, &error));
    CHECK(error.find("opacity") != std::string::npos);
    id.material.opacity = 1.0f;
    const vct::VoxelInstanceHandle instance = scene->addInstance(id, &error);
    REQUIRE(instance);
    CHECK_FALSE(scene->setTransform(instance, glm::mat4(NAN), &error));
    CHECK_FALSE(scene->removeMesh(mesh, &error));
    CHECK(error.find("used by 1 instance") != std::string::npos);
    CHECK(scene->removeInstance(instance, &error));
    CHECK(scene->removeMesh(mesh, &error));
    CHECK(scene->takeDirtyRegions().size() == 2);  // where the instance was added and removed (refusals mark nothing)
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("registered meshes voxelize as the application's own draws do", "[vct]", registeredMeshesEqualTheAppsDraws)
BACKEND_TEST("a voxel scene refuses bad meshes, buffers and instances", "[vct]", refusesBadMeshesAndInstances)
