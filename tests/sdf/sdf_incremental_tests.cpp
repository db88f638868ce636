// Incremental updates equal a from-scratch build: after many frames of moving the centre, moving, adding
// and removing static instances and animating a dynamic one, the decoded field (per voxel: state and
// all 512 stored samples) equals that of a new scene built once from the final state. Brick slots may
// differ; distances may not (the test asserts exact equality). Also with budgets so small that most
// work is deferred (CPU budgets) or overflows on the GPU (references, brick pool).
#include <glm/gtc/matrix_transform.hpp>

#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

struct World {
    scenes::SceneGeometry geometry;  // meshes: Cornell parts + a torus
    uint32_t torusMesh = 0;
};

World makeWorld() {
    World w;
    w.geometry = scenes::cornellBox();
    w.torusMesh = uint32_t(w.geometry.meshes.size());
    w.geometry.meshes.push_back(scenes::torus(60.0f, 20.0f, 2000));
    w.geometry.instances.clear();
    return w;
}

glm::mat4 torusAt(glm::vec3 p, float angle) {
    return glm::rotate(glm::translate(glm::mat4(1.0f), p), angle, glm::vec3(0.3f, 1.0f, 0.1f));
}

sdf::SceneDesc sceneDesc(TestDevice& td) {
    sdf::SceneDesc d;
    d.cascadeCount = 3;
    d.finestVoxelSize = 16.0f;  // cascade 0 spans 1024 mm: the Cornell box scrolls partly out of it
    d.atlasBricksPerAxis = 32;
    d.moverGrids = false;  // every dynamic instance re-voxelized: the field is exact (moverGridsComposite has them on)
    d.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
    return d;
}

// Final state, shared by both scenes.
struct FinalState {
    glm::vec3 center;
    std::vector<std::pair<uint32_t, glm::mat4>> statics;  // mesh, transform
    glm::mat4 dynamicTransform;
};

FinalState buildIncrementally(rhi::IDevice& device, sdf::SdfScene& scene, const World& w, std::vector<sdf::MeshHandle>& meshes, int frames,
                              bool settle) {
    FinalState f;
    std::vector<sdf::InstanceHandle> walls;
    for (uint32_t m = 0; m < w.torusMesh; ++m) walls.push_back(scene.addInstance({meshes[m], glm::mat4(1.0f)}));
    sdf::InstanceHandle a = scene.addInstance({meshes[w.torusMesh], torusAt({150, 200, 200}, 0.0f)});
    sdf::InstanceHandle b = scene.addInstance({meshes[w.torusMesh], torusAt({400, 420, 300}, 1.0f)});
    sdf::InstanceHandle c;
    sdf::InstanceDesc dyn{meshes[w.torusMesh], torusAt({280, 100, 150}, 0.0f), true};
    sdf::InstanceHandle d = scene.addInstance(dyn);
    glm::vec3 center(278, 274, 280);
    glm::mat4 aT(1.0f), dT(1.0f);
    for (int frame = 0; frame < frames; ++frame) {
        // The centre wanders by whole and fractional voxels on every axis, once by more than a window.
        center += glm::vec3(std::sin(frame * 1.3f) * 40.0f, std::cos(frame * 0.7f) * 25.0f, frame % 3 == 0 ? 31.0f : -17.0f);
        if (frame == frames / 2) center += glm::vec3(900.0f, 0.0f, 0.0f);
        if (frame == frames / 2 + 1) center -= glm::vec3(880.0f, 0.0f, 0.0f);
        aT = torusAt({150.0f + 10.0f * frame, 200.0f, 200.0f + 5.0f * frame}, 0.2f * frame);
        scene.setTransform(a, aT);
        if (frame == 3) scene.removeInstance(b);
        if (frame == 5) c = scene.addInstance({meshes[w.torusMesh], torusAt({300, 300, 450}, 2.0f)});
        if (frame == 6) scene.removeInstance(walls[2]);  // the back wall goes
        dT = torusAt({280.0f + 15.0f * std::sin(float(frame)), 100.0f, 150.0f + 9.0f * frame}, 0.5f * frame);
        scene.setTransform(d, dT);
        scene.update(center);
        device.endFrame();
    }
    // Settle: with budgets, keep updating (only the dynamic instance is rebuilt) until nothing is deferred
    // on the CPU and the GPU has reported no deferral for several updates in a row.
    for (int i = 0, clean = 0; settle && i < 400 && clean < 6; ++i) {
        sdf::UpdateReport r = scene.update(center);
        device.endFrame();
        const bool gpuClean = scene.latestStats().voxelsDeferredGpu == 0 && r.jobsRetried == 0;
        clean = (r.jobsDeferred == 0 && gpuClean) ? clean + 1 : 0;
    }
    f.center = center;
    for (uint32_t m = 0; m < w.torusMesh; ++m)
        if (m != 2) f.statics.push_back({m, glm::mat4(1.0f)});
    f.statics.push_back({w.torusMesh, aT});
    f.statics.push_back({w.torusMesh, torusAt({300, 300, 450}, 2.0f)});
    f.dynamicTransform = dT;
    return f;
}

sdf::FieldSnapshot buildFromScratch(TestDevice& td, const World& w, const FinalState& f) {
    auto scene = sdf::SdfScene::create(*td.device, sceneDesc(td));
    REQUIRE(scene);
    std::vector<sdf::MeshHandle> meshes = createMeshes(*scene, w.geometry);
    for (const auto& [mesh, t] : f.statics) scene->addInstance({meshes[mesh], t});
    scene->addInstance({meshes[w.torusMesh], f.dynamicTransform, true});
    scene->update(f.center);
    return scene->readField();
}

void incrementalEqualsScratch(const std::string& backend, const sdf::Budgets* budgets, int frames) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    World w = makeWorld();
    sdf::SceneDesc desc = sceneDesc(td);
    if (budgets) desc.budgets = *budgets;
    auto scene = sdf::SdfScene::create(*td.device, desc);
    REQUIRE(scene);
    std::vector<sdf::MeshHandle> meshes = createMeshes(*scene, w.geometry);
    FinalState f = buildIncrementally(*td.device, *scene, w, meshes, frames, budgets != nullptr);
    sdf::FieldSnapshot incremental = scene->readField();
    sdf::FieldSnapshot scratch = buildFromScratch(td, w, f);
    REQUIRE_NO_MESSAGES(td);
    FieldDifference diff = compareFields(incremental, scratch);
    // Bricks in use: the live ones, and the static field's kept under the dynamic torus's composites.
    uint64_t bricks = 0, bases = 0, incrementalBases = 0;
    for (uint32_t c = 0; c < 3; ++c) {
        for (uint32_t s : scratch.cascades[c].brickMap) bricks += s < 0xFFFFFFF0u;
        for (uint32_t s : scratch.cascades[c].baseMap) bases += s < 0xFFFFFFF0u;
        for (uint32_t s : incremental.cascades[c].baseMap) incrementalBases += s < 0xFFFFFFF0u;
    }
    INFO(backend << ": " << diff.voxelsCompared << " voxels, " << bricks << " bricks in the from-scratch field; "
                 << diff.stateMismatches << " state mismatches (first: " << diff.firstMismatch << "), "
                 << diff.brixelsDiffering << " brixels differ, largest difference " << diff.maxBrixelDifference);
    CHECK(bricks > 1000);
    CHECK(bases > 0);  // the torus is composited over static geometry somewhere
    CHECK(incrementalBases == bases);
    CHECK(diff.stateMismatches == 0);
    CHECK(diff.maxBrixelDifference == 0);
    const sdf::Stats stats = scene->latestStats();
    INFO("stats: update " << stats.update << ", bricks used " << stats.bricksUsed << ", deferred on GPU " << stats.voxelsDeferredGpu);
    CHECK(stats.update > 0);
    CHECK(stats.bricksUsed == bricks + bases);
}

void incrementalDefault(const std::string& backend) { incrementalEqualsScratch(backend, nullptr, 14); }

void incrementalSmallBudgets(const std::string& backend) {
    sdf::Budgets b;
    b.maxVoxelsPerUpdate = 20000;    // a full cascade is 262144: most work waits for later updates
    b.maxTrianglesPerUpdate = 7000;  // below the whole scene (8036)
    b.maxReferencesPerUpdate = 400000; // above what the dynamic torus needs per update
    b.maxJobsPerUpdate = 16;
    incrementalEqualsScratch(backend, &b, 8);
}

// A brick pool far too small: the GPU defers what does not fit, reports it, and corrupts nothing: every
// voxel it did build equals the from-scratch build with a large pool.
void poolExhausted(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    World w = makeWorld();
    auto build = [&](uint32_t bricksPerAxis, sdf::Stats* stats) {
        sdf::SceneDesc desc = sceneDesc(td);
        desc.atlasBricksPerAxis = bricksPerAxis;
        auto scene = sdf::SdfScene::create(*td.device, desc);
        REQUIRE(scene);
        std::vector<sdf::MeshHandle> meshes = createMeshes(*scene, w.geometry);
        for (uint32_t m = 0; m < w.torusMesh; ++m) scene->addInstance({meshes[m], glm::mat4(1.0f)});
        for (int i = 0; i < 4; ++i) {
            scene->update(glm::vec3(278, 274, 280));
            td.device->endFrame();
        }
        sdf::FieldSnapshot field = scene->readField();
        if (stats) *stats = scene->latestStats();
        return field;
    };
    sdf::Stats small{};
    sdf::FieldSnapshot starved = build(8, &small);  // 512 bricks
    sdf::FieldSnapshot full = build(32, nullptr);
    REQUIRE_NO_MESSAGES(td);
    CHECK(small.voxelsDeferredGpu > 0);
    CHECK(small.bricksUsed > 400);  // nearly all of the 512 (bricks found empty go back to the pool)
    uint64_t built = 0, unbuilt = 0, wrong = 0;
    for (uint32_t c = 0; c < 3; ++c)
        for (int i = 0; i < 64 * 64 * 64; ++i) {
            const glm::ivec3 v(i & 63, (i >> 6) & 63, i >> 12);
            const uint32_t a = starved.voxelState(c, v), b = full.voxelState(c, v);
            if (a == sdf::FieldSnapshot::kUnbuilt) {
                unbuilt++;
                continue;
            }
            built++;
            if ((a < 0xFFFFFFF0u) != (b < 0xFFFFFFF0u) || (a >= 0xFFFFFFF0u && a != b)) {
                wrong++;
                continue;
            }
            if (a < 0xFFFFFFF0u)
                for (int k = 0; k < 512; ++k) {
                    const glm::ivec3 bx(k & 7, (k >> 3) & 7, k >> 6);
                    if (starved.brixel(a, bx) != full.brixel(b, bx)) {
                        wrong++;
                        break;
                    }
                }
        }
    INFO(built << " voxels built, " << unbuilt << " left unbuilt, " << wrong << " differ; stats: deferred "
               << small.voxelsDeferredGpu << ", free " << small.bricksFree);
    CHECK(unbuilt > 0);
    CHECK(wrong == 0);
}

// Movers cost what they change: with static walls around it, a moving dynamic torus gathers its own
// triangles only (no full job, no static triangle), and a deforming one — its vertices rewritten in the
// application's own buffer every update — too. Either way the field equals, brixel by brixel, a from-scratch
// build with every instance static, in which one brick pass takes the minimum over all triangles at once.
// The mover is dense enough that its coarse bricks are split over several groups of the brick pass. When it
// stops it costs nothing, until a static box placed under it rebuilds its voxels: it is composited again.
void moversGatherTheirOwnTriangles(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    World w = makeWorld();
    const scenes::TriangleMesh& torus = w.geometry.meshes[w.torusMesh];
    const uint32_t torusTriangles = uint32_t(torus.indices.size() / 3);
    auto scene = sdf::SdfScene::create(dev, sceneDesc(td));
    REQUIRE(scene);
    std::vector<sdf::MeshHandle> meshes = createMeshes(*scene, w.geometry);
    for (uint32_t m = 0; m < w.torusMesh; ++m) scene->addInstance({meshes[m], glm::mat4(1.0f)});

    // The deforming torus: its positions in a buffer of ours, as an application's skinning output would be.
    auto deformed = [&](int frame) {
        std::vector<float> p = torus.positions;
        for (size_t v = 0; v < p.size(); v += 3) p[v + 1] *= 1.0f + 0.3f * std::sin(0.9f * float(frame) + 0.01f * p[v]);
        return p;
    };
    const float grow = 1.3f;  // declared bounds cover every frame's shape
    rhi::BufferHandle vb = dev.createBuffer({torus.positions.size() * 4, 0, rhi::BufferUsage::ShaderRead, "deforming positions"},
                                            deformed(0).data());
    rhi::BufferHandle ib = dev.createBuffer({torus.indices.size() * 4, 0, rhi::BufferUsage::ShaderRead, "deforming indices"},
                                            torus.indices.data());
    sdf::MeshBuffers mb;
    mb.vertexBuffer = vb;
    mb.vertexCount = uint32_t(torus.positions.size() / 3);
    mb.indexBuffer = ib;
    mb.triangleCount = torusTriangles;
    mb.boundsMin = glm::vec3(-80.0f, -20.0f * grow, -80.0f);
    mb.boundsMax = glm::vec3(80.0f, 20.0f * grow, 80.0f);
    mb.name = "deforming torus";
    sdf::MeshHandle deformingMesh = scene->createMesh(mb);
    REQUIRE(deformingMesh);
    const glm::mat4 deformingAt = glm::translate(glm::mat4(1.0f), glm::vec3(400.0f, 300.0f, 300.0f));
    scene->addInstance({deformingMesh, deformingAt, true});
    // The mover is dense enough that the brick pass splits its coarse bricks over several groups.
    const scenes::TriangleMesh dense = scenes::torus(60.0f, 20.0f, 24000);
    sdf::MeshHandle denseMesh = scene->createMesh({dense.positions.data(), uint32_t(dense.positions.size() / 3), dense.indices.data(),
                                                   uint32_t(dense.indices.size()), "dense torus"});
    const uint32_t denseTriangles = uint32_t(dense.indices.size() / 3);
    sdf::InstanceHandle mover = scene->addInstance({denseMesh, torusAt({200, 60, 200}, 0.0f), true});

    const glm::vec3 center(278, 274, 280);
    scene->update(center);  // the walls: full jobs
    dev.endFrame();
    glm::mat4 moverAt(1.0f);
    int frame = 1;
    for (; frame <= 6; ++frame) {
        moverAt = torusAt({200.0f + 13.0f * float(frame), 60.0f - 4.0f * float(frame), 200.0f + 7.0f * float(frame)}, 0.3f * float(frame));
        scene->setTransform(mover, moverAt);
        const std::vector<float> p = deformed(frame);
        dev.writeBuffer(vb, 0, p.data(), p.size() * 4);
        const sdf::UpdateReport r = scene->update(center);
        dev.endFrame();
        INFO("frame " << frame << ": " << r.jobs << " jobs (" << r.overlayJobs << " overlay), " << r.trianglesGathered << " triangles gathered ("
                      << r.overlayTrianglesGathered << " by the overlay), " << r.instancesGathered << " instances");
        CHECK(r.jobs == r.overlayJobs);
        CHECK(r.trianglesGathered == torusTriangles + denseTriangles);
        CHECK(r.overlayTrianglesGathered == torusTriangles + denseTriangles);
        CHECK(r.instancesGathered == 2);
        CHECK(r.jobsDeferred == 0);
    }
    // The mover stops: it costs nothing more (its mesh is the scene's, fixed), the deforming one goes on.
    {
        const std::vector<float> p = deformed(frame);
        dev.writeBuffer(vb, 0, p.data(), p.size() * 4);
        const sdf::UpdateReport r = scene->update(center);
        dev.endFrame();
        INFO("the mover still: " << r.trianglesGathered << " triangles gathered");
        CHECK(r.trianglesGathered == torusTriangles);
        ++frame;
    }
    // A static box placed where the still mover is: its full job builds the static field alone there, and the
    // still mover is composited over it again.
    std::vector<float> boxPositions;
    std::vector<uint32_t> boxIndices;
    {
        scenes::TriangleMesh box;
        scenes::addBox(box, glm::vec3(150.0f, 0.0f, 220.0f), glm::vec3(330.0f, 30.0f, 290.0f));
        boxPositions = box.positions;
        boxIndices = box.indices;
    }
    sdf::MeshHandle boxMesh = scene->createMesh({boxPositions.data(), uint32_t(boxPositions.size() / 3), boxIndices.data(),
                                                 uint32_t(boxIndices.size()), "box under the mover"});
    scene->addInstance({boxMesh, glm::mat4(1.0f)});
    {
        const std::vector<float> p = deformed(frame);
        dev.writeBuffer(vb, 0, p.data(), p.size() * 4);
        const sdf::UpdateReport r = scene->update(center);
        dev.endFrame();
        INFO("a static box under the still mover: " << r.jobs << " jobs (" << r.overlayJobs << " overlay), " << r.overlayTrianglesGathered
                                                     << " triangles gathered by the overlay");
        CHECK(r.overlayTrianglesGathered == torusTriangles + denseTriangles);
        ++frame;
    }
    sdf::FieldSnapshot incremental = scene->readField();
    const sdf::Stats stats = scene->latestStats();

    auto scratch = sdf::SdfScene::create(dev, sceneDesc(td));
    REQUIRE(scratch);
    std::vector<sdf::MeshHandle> scratchMeshes = createMeshes(*scratch, w.geometry);
    for (uint32_t m = 0; m < w.torusMesh; ++m) scratch->addInstance({scratchMeshes[m], glm::mat4(1.0f)});
    sdf::MeshHandle scratchDense = scratch->createMesh({dense.positions.data(), uint32_t(dense.positions.size() / 3), dense.indices.data(),
                                                        uint32_t(dense.indices.size()), "dense torus"});
    scratch->addInstance({scratchDense, moverAt});
    const std::vector<float> last = deformed(frame - 1);
    sdf::MeshHandle lastShape = scratch->createMesh({last.data(), uint32_t(last.size() / 3), torus.indices.data(),
                                                     uint32_t(torus.indices.size()), "deformed torus, last frame"});
    scratch->addInstance({lastShape, deformingAt});
    sdf::MeshHandle scratchBox = scratch->createMesh({boxPositions.data(), uint32_t(boxPositions.size() / 3), boxIndices.data(),
                                                      uint32_t(boxIndices.size()), "box under the mover"});
    scratch->addInstance({scratchBox, glm::mat4(1.0f)});
    scratch->update(center);
    sdf::FieldSnapshot reference = scratch->readField();
    REQUIRE_NO_MESSAGES(td);
    FieldDifference diff = compareFields(incremental, reference);
    uint64_t bases = 0;
    for (const auto& c : incremental.cascades)
        for (uint32_t b : c.baseMap) bases += b < 0xFFFFFFF0u;
    INFO(backend << ": " << diff.stateMismatches << " state mismatches (first: " << diff.firstMismatch << "), " << diff.brixelsDiffering
                 << " brixels differ, largest difference " << diff.maxBrixelDifference << "; " << bases << " static bricks under composites");
    CHECK(bases > 0);  // the mover passes near the floor: composites over static bricks were made
    INFO("stats of update " << stats.update << ": " << stats.bricksSplit << " bricks split over several groups");
    CHECK(stats.bricksSplit > 0);
    CHECK(diff.stateMismatches == 0);
    CHECK(diff.maxBrixelDifference == 0);
    dev.destroy(vb);
    dev.destroy(ib);
}

// Rigid movers at their footprint's cost: a rigid dynamic torus of the scene's own mesh is composited from
// its mover grid — no triangle of it is gathered, whatever it does: translate, rotate, scale uniformly — while
// a deforming one beside it is re-voxelized. The field then equals a from-scratch build with every instance
// static (exact distances) in its states and, within the stated tolerance, in its samples: a mover's sample
// is the exact distance to the nearest of the triangles nearest to its 27 lattice points, which is its exact
// distance wherever its own nearest triangle is among them.
void moverGridsComposite(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    rhi::IDevice& dev = *td.device;
    World w = makeWorld();
    const scenes::TriangleMesh& torus = w.geometry.meshes[w.torusMesh];
    const uint32_t torusTriangles = uint32_t(torus.indices.size() / 3);
    sdf::SceneDesc desc = sceneDesc(td);
    desc.moverGrids = true;
    auto scene = sdf::SdfScene::create(dev, desc);
    REQUIRE(scene);
    std::vector<sdf::MeshHandle> meshes = createMeshes(*scene, w.geometry);
    for (uint32_t m = 0; m < w.torusMesh; ++m) scene->addInstance({meshes[m], glm::mat4(1.0f)});
    // The deforming torus, in a buffer of ours.
    std::vector<float> shape = torus.positions;
    for (size_t v = 0; v < shape.size(); v += 3) shape[v + 1] *= 1.2f;
    rhi::BufferHandle vb = dev.createBuffer({shape.size() * 4, 0, rhi::BufferUsage::ShaderRead, "deforming positions"}, shape.data());
    rhi::BufferHandle ib = dev.createBuffer({torus.indices.size() * 4, 0, rhi::BufferUsage::ShaderRead, "deforming indices"},
                                            torus.indices.data());
    sdf::MeshBuffers mb;
    mb.vertexBuffer = vb;
    mb.vertexCount = uint32_t(shape.size() / 3);
    mb.indexBuffer = ib;
    mb.triangleCount = torusTriangles;
    mb.boundsMin = glm::vec3(-80.0f, -25.0f, -80.0f);
    mb.boundsMax = glm::vec3(80.0f, 25.0f, 80.0f);
    mb.name = "deforming torus";
    sdf::MeshHandle deformingMesh = scene->createMesh(mb);
    const glm::mat4 deformingAt = glm::translate(glm::mat4(1.0f), glm::vec3(400.0f, 300.0f, 300.0f));
    scene->addInstance({deformingMesh, deformingAt, true});
    sdf::InstanceDesc moverDesc{meshes[w.torusMesh], torusAt({200, 60, 200}, 0.0f), true};
    moverDesc.material = sdf::SurfaceMaterial{glm::vec3(0.2f, 0.7f, 0.3f), glm::vec3(0.0f)};
    sdf::InstanceHandle mover = scene->addInstance(moverDesc);
    // A second mover of the same mesh (one grid for both), beside the deforming torus: coarse voxels hold both
    // movers' chunks among the deforming triangles (the brick pass's many-reference path).
    sdf::InstanceHandle second = scene->addInstance({meshes[w.torusMesh], torusAt({380, 250, 330}, 1.0f), true});

    const glm::vec3 center(278, 274, 280);
    scene->update(center);
    dev.endFrame();
    glm::mat4 moverAt(1.0f);
    for (int frame = 1; frame <= 5; ++frame) {
        moverAt = torusAt({200.0f + 17.0f * float(frame), 70.0f + 9.0f * float(frame), 210.0f - 6.0f * float(frame)}, 0.45f * float(frame));
        const float scale = frame >= 4 ? 1.25f : 1.0f;  // a new scale: its grid is built once
        moverAt = glm::scale(moverAt, glm::vec3(scale));
        scene->setTransform(mover, moverAt);
        scene->setTransform(second, torusAt({380.0f - 5.0f * float(frame), 250.0f, 330.0f}, 1.0f + 0.2f * float(frame)));
        const sdf::UpdateReport r = scene->update(center);
        dev.endFrame();
        INFO("frame " << frame << ": " << r.overlayTrianglesGathered << " triangles gathered by the overlay, " << r.moverGridInstances
                      << " movers from grids, " << r.moverGridsBuilt << " grids built");
        CHECK(r.jobs == r.overlayJobs);
        CHECK(r.overlayTrianglesGathered == torusTriangles);  // the deforming torus alone
        CHECK(r.moverGridInstances == 2);
        CHECK(r.moverGridsBuilt == (frame == 4 ? 2u : 0u));  // a new scale: the grids are laid out and built again
    }
    sdf::FieldSnapshot composited = scene->readField();

    sdf::SceneDesc exact = sceneDesc(td);
    auto scratch = sdf::SdfScene::create(dev, exact);
    REQUIRE(scratch);
    std::vector<sdf::MeshHandle> scratchMeshes = createMeshes(*scratch, w.geometry);
    for (uint32_t m = 0; m < w.torusMesh; ++m) scratch->addInstance({scratchMeshes[m], glm::mat4(1.0f)});
    sdf::InstanceDesc still{scratchMeshes[w.torusMesh], moverAt};
    still.material = moverDesc.material;
    scratch->addInstance(still);
    scratch->addInstance({scratchMeshes[w.torusMesh], torusAt({380.0f - 25.0f, 250.0f, 330.0f}, 2.0f)});
    sdf::MeshHandle shapeMesh = scratch->createMesh({shape.data(), uint32_t(shape.size() / 3), torus.indices.data(),
                                                     uint32_t(torus.indices.size()), "deformed torus"});
    scratch->addInstance({shapeMesh, deformingAt});
    scratch->update(center);
    sdf::FieldSnapshot reference = scratch->readField();
    REQUIRE_NO_MESSAGES(td);
    FieldDifference diff = compareFields(composited, reference);
    // Per brixel of the voxels both build: how much farther (or nearer) the composite's sample is.
    uint64_t brixels = 0, nearer = 0, fartherThanOneStep = 0;
    for (uint32_t c = 0; c < composited.cascades.size(); ++c)
        for (int z = 0; z < 64; ++z)
            for (int y = 0; y < 64; ++y)
                for (int x = 0; x < 64; ++x) {
                    const uint32_t a = composited.voxelState(c, {x, y, z}), b = reference.voxelState(c, {x, y, z});
                    if (a >= sdf::FieldSnapshot::kNoBase || b >= sdf::FieldSnapshot::kNoBase) continue;
                    for (int k = 0; k < 512; ++k) {
                        const glm::ivec3 at(k & 7, (k >> 3) & 7, k >> 6);
                        const int d = int(composited.brixel(a, at)) - int(reference.brixel(b, at));
                        ++brixels;
                        nearer += d < -1;
                        fartherThanOneStep += d > 1;
                    }
                }
    INFO(backend << ": " << diff.voxelsCompared << " voxels, " << diff.stateMismatches << " state mismatches (first: " << diff.firstMismatch
                 << "); of " << brixels << " brixels " << diff.brixelsDiffering << " differ, " << fartherThanOneStep
                 << " by more than a step, " << nearer << " nearer by more than a step; largest difference " << diff.maxBrixelDifference);
    CHECK(diff.stateMismatches == 0);
    // A real triangle's distance: never nearer than the exact one (but for the rounding of the transform).
    CHECK(nearer == 0);
    // Farther where the sample's nearest triangle is not nearest to one of its 27 lattice points: found where
    // the surface curves within a cascade's cell (coarse cascades), by at most 0.4 brixel there.
    CHECK(diff.maxBrixelDifference <= 51);
    CHECK(fartherThanOneStep * 2000 <= brixels);
    dev.destroy(vb);
    dev.destroy(ib);
}

}  // namespace

BACKEND_TEST("sdf rigid movers composite from mover grids: no triangle gathered, distances within tolerance of exact", "[sdf]",
             moverGridsComposite)
BACKEND_TEST("sdf exhausted brick pool defers work without corrupting the field", "[sdf]", poolExhausted)
BACKEND_TEST("sdf incremental updates equal a from-scratch build", "[sdf]", incrementalDefault)
BACKEND_TEST("sdf incremental updates under small budgets converge to a from-scratch build", "[sdf]", incrementalSmallBudgets)
BACKEND_TEST("sdf movers and deforming meshes gather their own triangles only and build the exact field", "[sdf]",
             moversGatherTheirOwnTriangles)
