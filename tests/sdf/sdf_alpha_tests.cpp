// Alpha-tested instances (sdf::InstanceDesc::alphaTested): the bricks that hold their surfaces are flagged, the
// cells that opaque surfaces reach are listed, and the public trace reports hits on the cards (and only there)
// as alpha-tested; a ray that goes on past them (blSdfContinueRay) reaches what lies behind.
//
// Scene (metres, finest voxel 0.1): an opaque ground quad at y = 0, an alpha-tested card standing on it in the
// plane z = 0 (x in [-1, 1], y in [0, 1.5]), an opaque wall at z = 1.
#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

scenes::TriangleMesh quad(const char* name, glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 d) {
    scenes::TriangleMesh m;
    m.name = name;
    for (glm::vec3 p : {a, b, c, d}) m.positions.insert(m.positions.end(), {p.x, p.y, p.z});
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

scenes::SceneGeometry cardScene(bool cardAlphaTested) {
    scenes::SceneGeometry g;
    g.meshes.push_back(quad("ground", {-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}));
    g.meshes.push_back(quad("card", {-1, 0, 0}, {1, 0, 0}, {1, 1.5f, 0}, {-1, 1.5f, 0}));
    g.meshes.back().alphaCutoff = cardAlphaTested ? 0.5f : 0.0f;
    g.meshes.push_back(quad("wall", {-2, 0, 1}, {2, 0, 1}, {2, 2, 1}, {-2, 2, 1}));
    for (uint32_t i = 0; i < 3; ++i) g.instances.push_back({i, glm::mat4(1.0f)});
    g.computeBounds();
    return g;
}

struct Ray {
    glm::vec3 origin, direction;
    uint32_t continues;
};
struct Result {
    float t;
    uint32_t passed;
    bool alphaTested;
};

std::vector<Result> trace(TestDevice& td, sdf::SdfScene& scene, const std::vector<Ray>& rays) {
    rhi::IDevice& dev = *td.device;
    std::vector<glm::vec4> data;
    for (const Ray& r : rays) {
        data.push_back(glm::vec4(r.origin, 0.0f));
        data.push_back(glm::vec4(glm::normalize(r.direction), float(r.continues)));
    }
    rhi::BufferDesc rb;
    rb.size = data.size() * sizeof(glm::vec4);
    rb.usage = rhi::BufferUsage::ShaderRead;
    rb.debugName = "alpha test rays";
    rhi::BufferHandle rayBuffer = dev.createBuffer(rb, data.data());
    rhi::BufferDesc hb;
    hb.size = rb.size;
    hb.debugName = "alpha test hits";
    rhi::BufferHandle hitBuffer = dev.createBuffer(hb);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("sdf_tests/trace_rays.comp");
    REQUIRE(sd.blob);
    rhi::ShaderHandle shader = dev.createShader(sd);
    struct { uint32_t rayCount, start, end; float tMax; } p{uint32_t(rays.size()), 0, scene.desc().cascadeCount - 1, 100.0f};
    rhi::DispatchState s;
    s.shader = shader;
    s.label = "trace alpha test rays";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, rayBuffer, {}});
    s.bindings.storageBuffers.push({0, hitBuffer, {}, rhi::Access::Write});
    scene.traceBindings(s.bindings, {});
    REQUIRE(dev.dispatch(s, uint32_t(rays.size() + 63) / 64, 1, 1));
    std::vector<glm::vec4> hits(data.size());
    REQUIRE(dev.readBuffer(hitBuffer, 0, hb.size, hits.data()));
    dev.destroy(shader);
    dev.destroy(rayBuffer);
    dev.destroy(hitBuffer);
    std::vector<Result> out;
    for (size_t i = 0; i < rays.size(); ++i) {
        const float w = hits[2 * i + 1].w;
        out.push_back({hits[2 * i].x, uint32_t(w), w - std::floor(w) > 0.25f});
    }
    return out;
}

void alphaTestedInstances(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    for (bool alphaTested : {true, false}) {
        INFO("card alpha-tested: " << alphaTested);
        const scenes::SceneGeometry g = cardScene(alphaTested);
        sdf::SceneDesc desc;
        desc.cascadeCount = 3;
        desc.finestVoxelSize = 0.1f;
        desc.atlasBricksPerAxis = 32;
        desc.errorCallback = [&td](rhi::Severity, const std::string& m) { td.messages->push_back(m); };
        LoadedScene loaded = loadIntoSdf(*td.device, g, desc);
        REQUIRE(loaded.scene);
        loaded.scene->update(glm::vec3(0.0f, 0.5f, 0.5f));
        const sdf::FieldSnapshot f = loaded.scene->readField();

        // Flags in the finest cascade: bricks within a voxel of the card are flagged; the wall's, half a metre
        // away, are not; a flagged brick on the ground lists its bottom cells as opaque.
        uint32_t flaggedNearCard = 0, bricksNearCard = 0, flaggedAtWall = 0, groundCellsOpaque = 0, groundCellsChecked = 0;
        const sdf::FieldSnapshot::Cascade& c0 = f.cascades[0];
        for (int z = 0; z < 64; ++z)
            for (int y = 0; y < 64; ++y)
                for (int x = 0; x < 64; ++x) {
                    const uint32_t brick = f.voxelState(0, {x, y, z});
                    if (brick >= sdf::FieldSnapshot::kUnbuilt - 15) continue;
                    const glm::vec3 lo = glm::vec3(c0.origin + glm::ivec3(x, y, z)) * c0.voxelSize;
                    const bool flagged = (f.brickAabbs[brick] != 0xFFFFFFFFu) && (f.brickAabbs[brick] & sdf::FieldSnapshot::kAabbAlphaTested);
                    // The card's plane is a voxel boundary: the voxels on both sides hold it.
                    const bool cardInside = lo.z > -0.15f && lo.z < 0.05f && lo.x > -0.95f && lo.x < 0.85f && lo.y > 0.05f && lo.y < 1.35f;
                    if (cardInside) {
                        ++bricksNearCard;
                        if (flagged) ++flaggedNearCard;
                    }
                    if (lo.z > 0.9f && lo.z < 1.0f && flagged) ++flaggedAtWall;
                    if (flagged && lo.y > -0.15f && lo.y < 0.05f) {  // the ground's two voxel rows (y = 0 is a boundary), by the card
                        for (uint32_t cx = 0; cx < 4; ++cx) {
                            const float v = (0.0f - lo.y) / c0.voxelSize;
                            const uint32_t cy = std::min(3u, uint32_t(v * 4.0f));
                            for (uint32_t cz = 0; cz < 4; ++cz) {
                                const uint32_t bit = (cz * 4 + cy) * 4 + cx;
                                ++groundCellsChecked;
                                if (f.brickOpaqueCells[2 * brick + bit / 32] & (1u << (bit % 32))) ++groundCellsOpaque;
                            }
                        }
                    }
                }
        UNSCOPED_INFO("bricks through the card " << bricksNearCard << ", flagged " << flaggedNearCard << "; flagged at the wall " << flaggedAtWall
                                                 << "; ground cells in flagged bricks " << groundCellsChecked << ", opaque " << groundCellsOpaque);
        REQUIRE(bricksNearCard > 100);
        CHECK(flaggedNearCard == (alphaTested ? bricksNearCard : 0u));
        CHECK(flaggedAtWall == 0u);
        if (alphaTested) {
            REQUIRE(groundCellsChecked > 0);
            CHECK(groundCellsOpaque == groundCellsChecked);
        }

        // Rays: through the card's middle (stopping there, or going past it to the wall), down onto the ground
        // beside the card (inside a flagged brick: opaque all the same), straight at the wall away from the card.
        const std::vector<Ray> rays = {
            {{0.1f, 0.75f, -1.0f}, {0, 0, 1}, 0},   {{0.1f, 0.75f, -1.0f}, {0, 0, 1}, 4}, {{-0.4f, 0.5f, -1.0f}, {0.2f, 0.1f, 1}, 4},
            {{0.3f, 0.6f, 0.03f}, {0, -1, 0}, 4},   {{1.6f, 1.0f, 0.0f}, {0, 0, 1}, 4},
        };
        const std::vector<Result> r = trace(td, *loaded.scene, rays);
        for (size_t i = 0; i < r.size(); ++i) UNSCOPED_INFO("ray " << i << ": t " << r[i].t << " passed " << r[i].passed << " alpha " << r[i].alphaTested);
        const float tol = 0.05f;  // an epsilon (0.6 brixel) and the sphere tracer's step
        CHECK(std::abs(r[0].t - 1.0f) < tol);
        CHECK(r[0].alphaTested == alphaTested);
        if (alphaTested) {
            CHECK(std::abs(r[1].t - 2.0f) < tol);  // past the card to the wall
            CHECK(r[1].passed == 1);
            CHECK(!r[1].alphaTested);
            CHECK(r[2].passed == 1);
            CHECK(std::abs(r[2].t - 2.0f * glm::length(glm::vec3(0.2f, 0.1f, 1.0f))) < 2 * tol);
        } else {
            CHECK(std::abs(r[1].t - 1.0f) < tol);  // opaque card: nothing to go past
            CHECK(r[1].passed == 0);
        }
        CHECK(std::abs(r[3].t - 0.6f) < tol);  // the ground beside the card
        CHECK(!r[3].alphaTested);
        CHECK(r[3].passed == 0);
        CHECK(std::abs(r[4].t - 1.0f) < tol);
        CHECK(!r[4].alphaTested);
        REQUIRE_NO_MESSAGES(td);
    }
}

}  // namespace

BACKEND_TEST("sdf alpha-tested instances: flagged bricks, opaque cells, rays that go past the cards", "[sdf]", alphaTestedInstances)
