// The GGX specular lobe of metallic-roughness materials: no energy is created in a white furnace, smooth
// metal reflects nearly all of it, a sun's mirror highlight matches the formula, and the fast path's direct
// light matches the path tracer's on glossy surfaces.
#include <cmath>

#include "backend_test.h"
#include "image_metrics.h"
#include "path_tracer.h"
#include "raster_renderer.h"
#include "render_test_support.h"

using namespace bricklight;
using namespace bricklight::testing;

namespace {

scenes::SceneGeometry sphereUnderSky(float roughness, float metalness) {
    scenes::TriangleMesh m = scenes::icosphere(4);
    m.normals = m.positions;
    m.albedo = glm::vec3(1.0f);
    m.roughness = roughness;
    m.metalness = metalness;
    m.specular = true;
    return furnace(m);
}

double meanOverSphere(TestDevice& td, const scenes::SceneGeometry& s) {
    auto pt = traced(td, s, 32, 256);
    const render::Image c = pt->read(render::Aov::Combined), depth = pt->read(render::Aov::Depth);
    double sum = 0.0;
    size_t n = 0;
    for (size_t p = 0; p < size_t(32) * 32; ++p)
        if (depth.rgb[3 * p] > 0.0f) sum += c.rgb[3 * p + 1], n++;  // pixels that see the sphere everywhere
    REQUIRE(n > 200);
    return sum / double(n);
}

void furnaceEnergy(const std::string& backend) {
    // A white (albedo 1) sphere under a uniform sky of 1: what it reflects is its directional albedo,
    // at most 1. Single-scattering GGX loses energy as roughness grows (~0.6-0.8 at roughness 1);
    // smooth metal keeps nearly all; diffuse + dielectric coat stays at or below 1.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    const double smoothMetal = meanOverSphere(td, sphereUnderSky(0.2f, 1.0f));
    const double roughMetal = meanOverSphere(td, sphereUnderSky(1.0f, 1.0f));
    const double coated = meanOverSphere(td, sphereUnderSky(0.4f, 0.0f));
    WARN(backend << ": white furnace, mean reflected radiance: metal r=0.2 " << smoothMetal << ", metal r=1 " << roughMetal
                 << ", dielectric r=0.4 " << coated);
    CHECK(smoothMetal <= 1.01);
    CHECK(smoothMetal >= 0.93);
    CHECK(roughMetal <= 1.01);
    CHECK(roughMetal >= 0.4);
    CHECK(coated <= 1.01);
    CHECK(coated >= 0.85);
    REQUIRE_NO_MESSAGES(td);
}

void mirrorHighlight(const std::string& backend) {
    // A metal plane (F0 = 1, roughness 0.5) lit by a sun at 45 degrees, seen from the mirror direction:
    // L = D V F E cos with h = n: D = 1 / (pi a^2), V = 1 / (4 c sqrt(c^2 (1 - a^2) + a^2)), F = 1.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry s;
    scenes::TriangleMesh plane = groundPlane(50.0f, glm::vec3(1.0f));
    plane.metalness = 1.0f;
    plane.roughness = 0.5f;
    plane.specular = true;
    s.meshes.push_back(plane);
    s.instances.push_back({0, glm::mat4(1.0f)});
    s.environment.sunDirection = glm::normalize(glm::vec3(1, 1, 0));
    s.environment.sunIrradiance = glm::vec3(2.0f);
    s.camera = {glm::vec3(-3, 3, 0), glm::vec3(0), glm::vec3(0, 1, 0), 10.0f};
    s.computeBounds();
    const double c = std::sqrt(0.5), a2 = 0.0625, e = 2.0;
    const double expected = 1.0 / (M_PI * a2) * 1.0 / (4.0 * c * std::sqrt(c * c * (1 - a2) + a2)) * e * c;
    Pair both = makePair(td, s, 9, 16, 1, false);
    const double traced = both.tracer->read(render::Aov::Direct).at(4, 4).x, rastered = both.raster->read(render::Aov::Direct).at(4, 4).x;
    INFO("expected " << expected << ", path tracer " << traced << ", fast path " << rastered);
    CHECK(traced == Approx(expected).epsilon(2e-3));
    CHECK(rastered == Approx(expected).epsilon(2e-3));  // 16-bit G-buffer roughness
    REQUIRE_NO_MESSAGES(td);
}

void glossyDirectMatches(const std::string& backend) {
    // The atrium with glossy floor, walls and cloth: the fast path's direct light (256 samples) against
    // the path tracer's direct AOV (256 spp, pixel centres): relMSE below 0.02, means within 2 %.
    TestDevice td = makeDevice(backend);
    REQUIRE(td.device);
    scenes::SceneGeometry s = scenes::atrium();
    for (auto& m : s.meshes) {
        m.specular = true;
        m.roughness = 0.35f;
    }
    s.meshes[0].metalness = 0.7f;
    Pair both = makePair(td, s, 48, 256, 256, false);
    const render::ImageMetrics m = render::compareImages(both.raster->read(render::Aov::Direct), both.tracer->read(render::Aov::Direct));
    WARN("glossy atrium " << backend << ": rasterized direct vs path-traced direct: relMSE " << m.relMse << ", means " << m.meanA
                          << " / " << m.meanB);
    CHECK(m.relMse < 0.02);
    CHECK(m.meanA == Approx(m.meanB).epsilon(0.02));
    REQUIRE_NO_MESSAGES(td);
}

}  // namespace

BACKEND_TEST("brdf: white furnace creates no energy", "[render]", furnaceEnergy)
BACKEND_TEST("brdf: a sun's mirror highlight on rough metal", "[render]", mirrorHighlight)
BACKEND_TEST("brdf: glossy direct light matches the path tracer", "[render]", glossyDirectMatches)
