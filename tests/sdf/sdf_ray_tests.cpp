// Rays through the public trace API (tests/sdf/shaders/trace_rays.comp includes bricklight/trace.glsl)
// against exact CPU ray-triangle intersection, for a large random ray set.
//
// Agreement: both miss, or both hit with |t_gpu - t_exact| <= 1 brixel / max(cos, 0.25) (brixel of the
// cascade that answered). Excepted as grazing: rays whose exact hit has |cos| < 0.15, and GPU hits that
// lie within 1.1 brixel of a surface that the exact ray passes without touching (the sphere tracer stops
// at 0.6 brixel from a surface, so near misses are hits for it).
#include <random>

#include "bricklight/rhi.h"
#include "backend_test.h"
#include "sdf_test_support.h"

using namespace bricklight;
using namespace bricklight::sdftest;

namespace {

struct RayStats {
    uint32_t rays = 0, agree = 0, excepted = 0, hits = 0;
    double maxTError = 0.0;
    std::string firstDisagreement;
};

RayStats traceAndCompare(TestDevice& td, const scenes::SceneGeometry& g, uint32_t rayCount) {
    const glm::vec3 extent = g.boundsMax - g.boundsMin;
    const sdf::SceneDesc desc = modelSceneDesc(g, 3, td);
    LoadedScene loaded = loadIntoSdf(*td.device, g, desc);
    REQUIRE(loaded.scene);
    const glm::vec3 center = (g.boundsMin + g.boundsMax) * 0.5f;
    loaded.scene->update(center);

    Reference ref(g, desc.finestVoxelSize);
    const double brixel0 = desc.finestVoxelSize / 7.0;
    std::mt19937 rng(99);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<glm::vec4> rays;
    std::vector<glm::dvec3> origins, directions;
    while (origins.size() < rayCount) {
        glm::dvec3 o = glm::dvec3(g.boundsMin) + glm::dvec3(extent) * glm::dvec3(unit(rng), unit(rng), unit(rng)) * 1.2 -
                       glm::dvec3(extent) * 0.1;
        if (ref.distance(o, 3 * brixel0) < 3 * brixel0) continue;  // unsigned field: start off surfaces
        glm::dvec3 d(unit(rng) * 2 - 1, unit(rng) * 2 - 1, unit(rng) * 2 - 1);
        if (glm::length(d) < 0.1 || glm::length(d) > 1.0) continue;
        d = glm::normalize(d);
        origins.push_back(o);
        directions.push_back(d);
        rays.push_back(glm::vec4(glm::vec3(o), 0.0f));
        rays.push_back(glm::vec4(glm::vec3(d), 0.0f));
    }
    rhi::IDevice& dev = *td.device;
    rhi::BufferDesc rb;
    rb.size = rays.size() * sizeof(glm::vec4);
    rb.usage = rhi::BufferUsage::ShaderRead;
    rb.debugName = "rays";
    rhi::BufferHandle rayBuffer = dev.createBuffer(rb, rays.data());
    rhi::BufferDesc hb;
    hb.size = rays.size() * sizeof(glm::vec4);
    hb.debugName = "hits";
    rhi::BufferHandle hitBuffer = dev.createBuffer(hb);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("sdf_tests/trace_rays.comp");
    REQUIRE(sd.blob);
    rhi::ShaderHandle shader = dev.createShader(sd);
    const float tMax = 2.0f * glm::length(extent);
    struct { uint32_t rayCount, start, end; float tMax; } p{rayCount, 0, desc.cascadeCount - 1, tMax};
    rhi::DispatchState s;
    s.shader = shader;
    s.label = "trace test rays";
    s.bindings.constants.push(rhi::constants(0, p));
    s.bindings.readBuffers.push({0, rayBuffer, {}});
    s.bindings.storageBuffers.push({0, hitBuffer, {}, rhi::Access::Write});
    loaded.scene->traceBindings(s.bindings, {});
    REQUIRE(dev.dispatch(s, (rayCount + 63) / 64, 1, 1));
    std::vector<glm::vec4> hits(rays.size());
    REQUIRE(dev.readBuffer(hitBuffer, 0, hb.size, hits.data()));
    REQUIRE_NO_MESSAGES(td);

    RayStats st;
    for (uint32_t i = 0; i < rayCount; ++i) {
        const glm::vec4 h = hits[2 * i];
        const bool gpuHit = h.x >= 0.0f;
        const double brixel = brixel0 * double(1u << uint32_t(h.y));
        double tExact = 0, cosine = 1;
        const bool cpuHit = ref.intersect(origins[i], directions[i], 0.0, tMax, &tExact, &cosine);
        st.rays++;
        if (cpuHit) st.hits++;
        bool agree = false, excepted = false;
        if (cpuHit && cosine < 0.15) {
            excepted = true;
        } else if (gpuHit && cpuHit) {
            const double err = std::fabs(double(h.x) - tExact);
            agree = err <= brixel / std::max(cosine, 0.25);
            if (agree) st.maxTError = std::max(st.maxTError, err / brixel);
        } else {
            agree = !gpuHit && !cpuHit;
        }
        if (!agree && !excepted && gpuHit && (!cpuHit || h.x < tExact)) {
            const glm::dvec3 at = origins[i] + directions[i] * double(h.x);
            excepted = ref.distance(at, 2.0 * brixel) <= 1.1 * brixel;
        }
        if (excepted) st.excepted++;
        else if (agree) st.agree++;
        else if (st.firstDisagreement.empty())
            st.firstDisagreement = "ray " + std::to_string(i) + ": gpu t " + std::to_string(h.x) + " (cascade " +
                                   std::to_string(int(h.y)) + ", " + std::to_string(int(h.z)) + " iterations), exact " +
                                   (cpuHit ? "t " + std::to_string(tExact) + " cos " + std::to_string(cosine) : std::string("miss"));
    }
    dev.destroy(rayBuffer);
    dev.destroy(hitBuffer);
    dev.destroy(shader);
    return st;
}

void raysAgree(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    std::string error;
    std::vector<std::pair<const char*, scenes::SceneGeometry>> scenesToTest;
    scenesToTest.emplace_back("cornell", scenes::cornellBox());
    scenesToTest.emplace_back("spider.obj", scenes::loadModel(testModelPath("OBJ/spider.obj"), &error));
    scenesToTest.emplace_back("Wuson.ply", scenes::loadModel(testModelPath("PLY/Wuson.ply"), &error));
    for (auto& [name, geometry] : scenesToTest) {
        REQUIRE(!geometry.meshes.empty());
        RayStats st = traceAndCompare(td, geometry, 4096);
        const uint32_t judged = st.rays - st.excepted;
        const double rate = double(st.agree) / double(std::max(1u, judged));
        INFO(name << " on " << backend << ": " << st.rays << " rays, " << st.hits << " exact hits, " << st.excepted
                  << " grazing, agreement " << rate * 100 << "% of " << judged << ", largest t error " << st.maxTError
                  << " brixel; first disagreement: " << st.firstDisagreement);
        WARN(name << " on " << backend << ": agreement " << rate * 100 << "% of " << judged << " (" << st.excepted
                  << " grazing excepted), largest t error " << st.maxTError << " brixel");
        CHECK(rate >= 0.99);
        CHECK(st.excepted <= st.rays / 10);
        CHECK(st.hits >= st.rays / 10);
    }
}

}  // namespace

BACKEND_TEST("sdf rays agree with exact ray-triangle intersection", "[sdf]", raysAgree)
