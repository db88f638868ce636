// Bad input: each a clear error naming the object and the problem that changes nothing, or a documented
// deferral (counted in stats) - never a crash, a hang or a corrupted field.
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

struct Harness {
    TestDevice td;
    std::vector<std::string> errors;
    std::unique_ptr<sdf::SdfScene> scene;
    explicit Harness(const std::string& backend, sdf::SceneDesc desc = {}) : td(makeDevice(backend)) {
        REQUIRE(td.device);
        if (desc.finestVoxelSize == 0.0f) desc.finestVoxelSize = 0.1f;
        desc.cascadeCount = std::min(desc.cascadeCount, 3u);
        desc.atlasBricksPerAxis = 16;
        desc.errorCallback = [this](rhi::Severity, const std::string& m) { errors.push_back(m); };
        scene = sdf::SdfScene::create(*td.device, desc);
        REQUIRE(scene);
    }
    // The last message contains every fragment; clears the list.
    void expectError(std::initializer_list<const char*> fragments) {
        REQUIRE(!errors.empty());
        for (const char* f : fragments) {
            INFO("message: " << errors.back() << " / expected to contain: " << f);
            CHECK(errors.back().find(f) != std::string::npos);
        }
        errors.clear();
    }
};

const float kQuad[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
const uint32_t kQuadIndices[] = {0, 1, 2, 0, 2, 3};

void badInput(const std::string& backend) {
    Harness h(backend);
    sdf::SdfScene& s = *h.scene;

    // Meshes from CPU arrays.
    const float nanQuad[] = {0, 0, 0, NAN, 0, 0, 1, 1, 0, 0, 1, 0};
    CHECK(!s.createMesh({nanQuad, 4, kQuadIndices, 6, "nan quad"}));
    h.expectError({"'nan quad'", "vertex 1", "non-finite"});
    const float infQuad[] = {0, 0, 0, 1, 0, 0, INFINITY, 1, 0, 0, 1, 0};
    CHECK(!s.createMesh({infQuad, 4, kQuadIndices, 6, "inf quad"}));
    h.expectError({"'inf quad'", "vertex 2", "non-finite"});
    const uint32_t badIndices[] = {0, 1, 7};
    CHECK(!s.createMesh({kQuad, 4, badIndices, 3, "bad indices"}));
    h.expectError({"'bad indices'", "index 2", "out of range"});
    CHECK(!s.createMesh({kQuad, 4, kQuadIndices, 0, "empty"}));
    h.expectError({"'empty'", "empty mesh"});
    CHECK(!s.createMesh({kQuad, 4, kQuadIndices, 5, "ragged"}));
    h.expectError({"'ragged'", "multiple of 3"});

    // Meshes from GPU buffers.
    rhi::BufferDesc vd;
    vd.size = sizeof(kQuad);
    vd.usage = rhi::BufferUsage::ShaderRead;
    rhi::BufferHandle vb = h.td.device->createBuffer(vd, kQuad);
    rhi::BufferDesc id;
    id.size = sizeof(kQuadIndices);
    id.usage = rhi::BufferUsage::ShaderRead;
    rhi::BufferHandle ib = h.td.device->createBuffer(id, kQuadIndices);
    sdf::MeshBuffers mb;
    mb.vertexBuffer = vb;
    mb.vertexCount = 4;
    mb.indexBuffer = ib;
    mb.triangleCount = 2;
    mb.boundsMax = glm::vec3(1, 1, 0);
    mb.name = "gpu quad";
    sdf::MeshBuffers bad = mb;
    bad.vertexBuffer = rhi::BufferHandle{9999};
    CHECK(!s.createMesh(bad));
    h.expectError({"'gpu quad'", "vertexBuffer", "not a live buffer"});
    bad = mb;
    bad.vertexCount = 5;
    CHECK(!s.createMesh(bad));
    h.expectError({"'gpu quad'", "beyond the vertex buffer"});
    bad = mb;
    bad.triangleCount = 3;
    CHECK(!s.createMesh(bad));
    h.expectError({"'gpu quad'", "beyond the index buffer"});
    bad = mb;
    bad.vertexStride = 14;
    CHECK(!s.createMesh(bad));
    h.expectError({"'gpu quad'", "multiples of 4"});
    bad = mb;
    bad.boundsMin = glm::vec3(NAN);
    CHECK(!s.createMesh(bad));
    h.expectError({"'gpu quad'", "bounds"});

    // Instances.
    sdf::MeshHandle quad = s.createMesh({kQuad, 4, kQuadIndices, 6, "quad"});
    REQUIRE(quad);
    CHECK(!s.addInstance({sdf::MeshHandle{12345}, glm::mat4(1.0f)}));
    h.expectError({"mesh 12345", "not a live mesh"});
    glm::mat4 nanTransform(1.0f);
    nanTransform[3][0] = NAN;
    CHECK(!s.addInstance({quad, nanTransform}));
    h.expectError({"'quad'", "non-finite"});
    glm::mat4 projective(1.0f);
    projective[2][3] = 1.0f;
    CHECK(!s.addInstance({quad, projective}));
    h.expectError({"'quad'", "not affine"});
    sdf::InstanceHandle inst = s.addInstance({quad, glm::mat4(1.0f)});
    REQUIRE(inst);
    CHECK(!s.setTransform(sdf::InstanceHandle{777}, glm::mat4(1.0f)));
    h.expectError({"instance", "777", "not a live instance"});
    CHECK(!s.setTransform(inst, nanTransform));
    h.expectError({"instance", "non-finite"});
    CHECK(!s.removeInstance(sdf::InstanceHandle{777}));
    h.expectError({"777", "not a live instance"});
    CHECK(!s.destroyMesh(quad));
    h.expectError({"'quad'", "still used"});
    s.update(glm::vec3(NAN));
    h.expectError({"centre", "not finite"});

    // GPU-side bad data in the app's buffers: NaN positions and indices out of range are dropped on the
    // GPU and counted (the CPU never sees these buffers' contents).
    const float gpuVerts[] = {0, 0, 0, 1, 0, 0, 1, 1, 0, NAN, 1, 0, 0.5f, 0.5f, 0.5f};
    const uint32_t gpuIndices[] = {0, 1, 2, 0, 2, 3, 0, 1, 9, 0, 1, 4};  // 2nd: NaN vertex, 3rd: index 9
    rhi::BufferHandle vb2 = h.td.device->createBuffer({sizeof(gpuVerts), 0, rhi::BufferUsage::ShaderRead, "verts"}, gpuVerts);
    rhi::BufferHandle ib2 = h.td.device->createBuffer({sizeof(gpuIndices), 0, rhi::BufferUsage::ShaderRead, "indices"}, gpuIndices);
    sdf::MeshBuffers dirty;
    dirty.vertexBuffer = vb2;
    dirty.vertexCount = 5;
    dirty.indexBuffer = ib2;
    dirty.triangleCount = 4;
    dirty.boundsMax = glm::vec3(1, 1, 0.5f);
    dirty.name = "dirty gpu mesh";
    sdf::MeshHandle dm = s.createMesh(dirty);
    REQUIRE(dm);
    s.addInstance({dm, glm::translate(glm::mat4(1.0f), glm::vec3(2, 0, 0))});
    s.update(glm::vec3(0.5f));
    h.td.device->waitIdle();
    s.update(glm::vec3(0.5f));  // polls the read-back
    const sdf::Stats st = s.latestStats();
    CHECK(st.trianglesRejected == 2);
    CHECK(st.trianglesProcessed >= 4);  // the quad and two good triangles of the GPU mesh
    CHECK(h.errors.empty());
    REQUIRE_NO_MESSAGES(h.td);
    h.td.device->destroy(vb);
    h.td.device->destroy(ib);
    h.td.device->destroy(vb2);
    h.td.device->destroy(ib2);
}

void badDescriptions(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    std::vector<std::string> errors;
    auto attempt = [&](sdf::SceneDesc d, const char* fragment) {
        d.errorCallback = [&](rhi::Severity, const std::string& m) { errors.push_back(m); };
        Error error;
        CHECK(!sdf::SdfScene::create(*td.device, d, &error));
        INFO(error.message);
        CHECK(error.message.find(fragment) != std::string::npos);
    };
    sdf::SceneDesc d;
    d.finestVoxelSize = 0.1f;
    d.cascadeCount = 0;
    attempt(d, "cascadeCount");
    d.cascadeCount = 17;
    attempt(d, "cascadeCount");
    d.cascadeCount = 2;
    d.finestVoxelSize = -1.0f;
    attempt(d, "finestVoxelSize");
    d.finestVoxelSize = NAN;
    attempt(d, "finestVoxelSize");
    d.finestVoxelSize = 0.1f;
    d.atlasBricksPerAxis = 0;
    attempt(d, "atlasBricksPerAxis");
    d.atlasBricksPerAxis = 8;
    d.budgets.maxReferencesPerUpdate = 0;
    attempt(d, "budget");
    d.budgets = {};
    d.maxInstances = 1;
    d.errorCallback = [&](rhi::Severity, const std::string& m) { errors.push_back(m); };
    auto scene = sdf::SdfScene::create(*td.device, d);
    REQUIRE(scene);
    sdf::MeshHandle quad = scene->createMesh({kQuad, 4, kQuadIndices, 6, "quad"});
    CHECK(scene->addInstance({quad, glm::mat4(1.0f)}));
    errors.clear();
    CHECK(!scene->addInstance({quad, glm::mat4(1.0f)}));
    REQUIRE(!errors.empty());
    CHECK(errors.back().find("maxInstances") != std::string::npos);
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("sdf bad meshes, instances and GPU data give clear errors or counted rejections", "[sdf]", badInput)
BACKEND_TEST("sdf bad scene descriptions and capacity give clear errors", "[sdf]", badDescriptions)
