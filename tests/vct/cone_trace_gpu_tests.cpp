// Cone tracing through the clip-map on both backends (bricklight/cone_trace.glsl via a test shader): inside a
// closed box whose walls send radiance 1 every cone gathers about 1 and ends opaque; a cone that leaves
// through an open side gathers nothing and stays open.
#include <catch2/catch.hpp>

#include <cmath>

#include "backend_test.h"
#include "test_device.h"
#include "voxelize_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

std::vector<Triangle> inwardBox(const glm::vec3& lo, const glm::vec3& hi) {
    std::vector<Triangle> box = boxTriangles(lo, hi);
    for (Triangle& t : box) t.normal = -t.normal;
    return box;
}

std::vector<glm::vec3> directions() {
    std::vector<glm::vec3> d;
    for (int a = 0; a < 3; ++a)
        for (int s = -1; s <= 1; s += 2) {
            glm::vec3 v(0.0f);
            v[a] = float(s);
            d.push_back(v);
        }
    for (int i = 0; i < 8; ++i) d.push_back(glm::normalize(glm::vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
    return d;
}

void conesInsideAnEmissiveBox(const std::string& backend, vct::EmittanceMode mode) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc = testClipmapDesc(4, mode);
    VoxelizeHarness h(td, desc);
    Error error;
    REQUIRE(h.clipmap().update(glm::vec3(16.5f), &error));
    const glm::vec3 one(1.0f);
    h.draw(inwardBox(glm::vec3(6.5f), glm::vec3(25.5f)), vct::VoxelMaterial{}, &one);
    h.clipmap().finishVoxelization();
    std::vector<ConeIn> cones;
    for (const glm::vec3& d : directions())
        for (float factor : {0.25f, 0.6f, 1.2f}) cones.push_back({glm::vec4(16.0f, 16.0f, 16.0f, factor), glm::vec4(d, 3.0f)});
    const std::vector<ConeOut> results = traceCones(td, h, cones);
    // Measured (anisotropic / isotropic): cones along the axes gather 0.99 / 0.89 (factor 0.25), 0.91 / 0.76 (0.6),
    // 0.46 / 0.64 (1.2) and end 0.99, 0.91, 0.51 opaque — the widest cones' last samples read the coarsest level's
    // first mip, whose 16-unit voxels hold the 19-unit box's walls and the space around them (0.72 / 0.60 and 0.72
    // opaque when they undersampled the coarsest level instead); cones into the corners, where coarse voxels hold
    // the corner and the empty space around it, 0.58 / 1.23, 0.44 / 1.00, 0.41 / 1.06.
    for (size_t i = 0; i < cones.size(); ++i) {
        const ConeOut& r = results[i];
        INFO("cone " << i << " direction " << cones[i].direction.x << "," << cones[i].direction.y << "," << cones[i].direction.z << " factor "
                     << cones[i].origin.w << ": radiance " << r.radiance.x << " ambient " << r.ambient << " opacity " << r.finalOpacity
                     << " samples " << r.samples);
        const float factor = cones[i].origin.w;
        const bool diagonal = std::abs(cones[i].direction.x) < 0.9f && std::abs(cones[i].direction.y) < 0.9f && std::abs(cones[i].direction.z) < 0.9f;
        CHECK(r.ambient > 0.95f);  // nothing within 3 voxels of the centre
        CHECK(r.radiance.y == Approx(r.radiance.x).epsilon(1e-3));
        CHECK(r.radiance.z == Approx(r.radiance.x).epsilon(1e-3));
        if (diagonal) {
            CHECK(r.finalOpacity > 0.25f);
            CHECK(r.radiance.x > 0.15f);
            CHECK(r.radiance.x < 1.3f);
        } else {
            CHECK(r.finalOpacity > (factor < 0.5f ? 0.97f : factor < 1.0f ? 0.85f : 0.45f));
            CHECK(r.radiance.x > (factor < 0.5f ? 0.85f : factor < 1.0f ? 0.7f : 0.4f));
            CHECK(r.radiance.x < 1.15f);
        }
    }
    REQUIRE_NO_MESSAGES(td);
}

void conesThroughAnOpenSide(const std::string& backend) {
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    vct::ClipmapDesc desc = testClipmapDesc(2);
    VoxelizeHarness h(td, desc);
    Error error;
    REQUIRE(h.clipmap().update(glm::vec3(16.5f), &error));
    // One wall at x = 25.5 facing −x, sending 2.
    std::vector<Triangle> box = inwardBox(glm::vec3(6.5f), glm::vec3(25.5f)), wall;
    for (const Triangle& t : box)
        if (t.normal.x < -0.5f) wall.push_back(t);
    REQUIRE(wall.size() == 2);
    const glm::vec3 two(2.0f);
    h.draw(wall, vct::VoxelMaterial{}, &two);
    h.clipmap().finishVoxelization();
    const std::vector<ConeOut> r = traceCones(td, h, {{glm::vec4(16.0f, 16.0f, 16.0f, 0.3f), glm::vec4(1.0f, 0.0f, 0.0f, 3.0f)},
                                                     {glm::vec4(16.0f, 16.0f, 16.0f, 0.3f), glm::vec4(-1.0f, 0.0f, 0.0f, 3.0f)},
                                                     {glm::vec4(16.0f, 16.0f, 16.0f, 0.3f), glm::vec4(0.0f, 1.0f, 0.0f, 3.0f)}});
    INFO("towards the wall: " << r[0].radiance.x << " opacity " << r[0].finalOpacity << "; away: " << r[1].radiance.x << " opacity "
                              << r[1].finalOpacity << "; along it: " << r[2].radiance.x << " opacity " << r[2].finalOpacity);
    CHECK(r[0].radiance.x > 1.5f);
    CHECK(r[0].radiance.x < 2.5f);
    CHECK(r[0].finalOpacity > 0.95f);  // 0.956: the last samples read mip 1, whose 4-unit voxels hold the wall and the space behind
    CHECK(r[1].radiance.x == 0.0f);
    CHECK(r[1].finalOpacity == 0.0f);
    CHECK(r[2].radiance.x < 0.2f);  // the wall lies 9.5 voxels off the cone's axis
    REQUIRE_NO_MESSAGES(td);
}

void anisotropicBox(const std::string& backend) { conesInsideAnEmissiveBox(backend, vct::EmittanceMode::Anisotropic); }
void isotropicBox(const std::string& backend) { conesInsideAnEmissiveBox(backend, vct::EmittanceMode::Isotropic); }

}  // namespace

BACKEND_TEST("cones inside an emissive box gather its radiance (anisotropic)", "[vct][quick]", anisotropicBox)
BACKEND_TEST("cones inside an emissive box gather its radiance (isotropic)", "[vct]", isotropicBox)
BACKEND_TEST("cones see a lit wall ahead and nothing through an open side", "[vct]", conesThroughAnOpenSide)
