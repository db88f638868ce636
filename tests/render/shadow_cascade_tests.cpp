// The sun's cascade fitting on the CPU (examples/demo_renderer/shadow_cascades.cpp): the cascades cover the view
// frustum up to the shadow distance, a moving camera shifts each map by whole texels, a turning one keeps each
// cascade's size.
#include <catch2/catch.hpp>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

#include "shadow_cascades.h"

using namespace bricklight::render;

namespace {

CascadeFitDesc baseDesc() {
    CascadeFitDesc d;
    d.eye = glm::vec3(1.3f, 2.1f, -4.7f);
    d.forward = glm::normalize(glm::vec3(0.3f, -0.2f, 1.0f));
    d.verticalFovDegrees = 60.0f;
    d.aspect = 1.5f;
    d.nearPlane = 0.05f;
    d.shadowDistance = 60.0f;
    d.splitLambda = 0.75f;
    d.resolution = 1024;
    d.sunDirection = glm::normalize(glm::vec3(0.5f, 0.8f, -0.35f));
    d.sceneMin = glm::vec3(-80.0f);
    d.sceneMax = glm::vec3(80.0f);
    return d;
}

// A point of the view frustum: screen position (u, v) in [-1, 1]², view distance z.
glm::vec3 frustumPoint(const CascadeFitDesc& d, float u, float v, float z) {
    const glm::vec3 f = glm::normalize(d.forward);
    const glm::vec3 right = glm::normalize(glm::cross(f, glm::vec3(0, 1, 0)));
    const glm::vec3 up = glm::cross(right, f);
    const float tanV = std::tan(glm::radians(d.verticalFovDegrees) * 0.5f), tanH = tanV * d.aspect;
    return d.eye + f * z + right * (u * tanH * z) + up * (v * tanV * z);
}

}  // namespace

TEST_CASE("shadow cascades: splits run from the near plane to the shadow distance", "[cpu][shadows]") {
    for (float lambda : {0.0f, 0.5f, 0.75f, 1.0f}) {
        const auto s = cascadeSplits(0.05f, 60.0f, lambda);
        CHECK(s[0] == 0.05f);
        CHECK(s[kShadowCascades] == 60.0f);
        for (uint32_t i = 0; i < kShadowCascades; ++i) CHECK(s[i] < s[i + 1]);
    }
    const auto uniform = cascadeSplits(0.0f, 80.0f, 0.0f);
    CHECK(uniform[1] == Approx(20.0f));
    CHECK(uniform[2] == Approx(40.0f));
    // Logarithmic: equal ratios from max(near, far/1000) on.
    const auto log = cascadeSplits(1.0f, 1000.0f, 1.0f);
    CHECK(log[2] / log[1] == Approx(log[3] / log[2]).epsilon(1e-4));
    CHECK(log[1] == Approx(std::pow(1000.0f, 0.25f)).epsilon(1e-4));
}

TEST_CASE("shadow cascades: together they cover the view frustum up to the shadow distance", "[cpu][shadows]") {
    for (float lambda : {0.0f, 0.75f, 1.0f}) {
        CascadeFitDesc d = baseDesc();
        d.splitLambda = lambda;
        const auto cascades = fitCascades(d);
        // Inside the map with the PCF border to spare, and inside the depth range.
        const float inner = 1.0f - 2.0f * float(kShadowBorderTexels - 1) / float(d.resolution);
        uint32_t outside = 0, samples = 0;
        for (int k = 0; k <= 40; ++k)
            for (int j = 0; j <= 16; ++j)
                for (int i = 0; i <= 16; ++i) {
                    const float t = float(k) / 40.0f;
                    const float z = d.nearPlane + (d.shadowDistance - d.nearPlane) * t;
                    const glm::vec3 p = frustumPoint(d, -1.0f + 2.0f * float(i) / 16.0f, -1.0f + 2.0f * float(j) / 16.0f, z);
                    bool held = false;
                    for (const ShadowCascade& c : cascades) {
                        if (z < c.splitNear || z > c.splitFar) continue;
                        const glm::vec4 clip = c.viewProjection * glm::vec4(p, 1.0f);
                        held = held || (std::fabs(clip.x) <= inner && std::fabs(clip.y) <= inner && clip.z >= 0.0f && clip.z <= 1.0f);
                    }
                    outside += held ? 0 : 1;
                    samples++;
                }
        INFO("lambda " << lambda << ": " << outside << " of " << samples << " frustum points outside every cascade");
        CHECK(outside == 0);
        CHECK(cascades[0].splitNear == d.nearPlane);
        CHECK(cascades[kShadowCascades - 1].splitFar == d.shadowDistance);
        for (uint32_t i = 0; i + 1 < kShadowCascades; ++i) {
            CHECK(cascades[i].splitFar == cascades[i + 1].splitNear);
            CHECK(cascades[i].radius < cascades[i + 1].radius);
        }
    }
}

TEST_CASE("shadow cascades: a moving camera shifts each map by whole texels", "[cpu][shadows]") {
    const CascadeFitDesc d = baseDesc();
    const auto before = fitCascades(d);
    for (const glm::vec3 step : {glm::vec3(0.0137f, 0.0f, 0.0f), glm::vec3(0.21f, -0.05f, 0.33f), glm::vec3(-1.7f, 0.4f, 2.9f)}) {
        CascadeFitDesc moved = d;
        moved.eye += step;
        const auto after = fitCascades(moved);
        for (uint32_t i = 0; i < kShadowCascades; ++i) {
            CHECK(after[i].radius == before[i].radius);
            CHECK(after[i].texelSize == before[i].texelSize);
            const glm::vec2 texels = (after[i].origin - before[i].origin) / before[i].texelSize;
            INFO("cascade " << i << " moved by " << texels.x << ", " << texels.y << " texels");
            CHECK(std::fabs(texels.x - std::round(texels.x)) < 1e-3f);
            CHECK(std::fabs(texels.y - std::round(texels.y)) < 1e-3f);
            // The matrices agree: a world point lands on the same texel grid, shifted by those whole texels.
            const glm::vec3 p(3.0f, 0.5f, 7.0f);
            const glm::vec2 a = (glm::vec2(before[i].viewProjection * glm::vec4(p, 1.0f)) * 0.5f + 0.5f) * float(d.resolution);
            const glm::vec2 b = (glm::vec2(after[i].viewProjection * glm::vec4(p, 1.0f)) * 0.5f + 0.5f) * float(d.resolution);
            const glm::vec2 shift = a - b;
            CHECK(std::fabs(shift.x - std::round(shift.x)) < 2e-2f);
            CHECK(std::fabs(shift.y - std::round(shift.y)) < 2e-2f);
        }
    }
}

TEST_CASE("shadow cascades: a turning camera keeps each cascade's size", "[cpu][shadows]") {
    const CascadeFitDesc d = baseDesc();
    const auto before = fitCascades(d);
    for (float degrees : {1.0f, 17.0f, 90.0f, 200.0f}) {
        CascadeFitDesc turned = d;
        const glm::mat4 r = glm::rotate(glm::mat4(1.0f), glm::radians(degrees), glm::normalize(glm::vec3(0.2f, 1.0f, 0.1f)));
        turned.forward = glm::vec3(r * glm::vec4(d.forward, 0.0f));
        const auto after = fitCascades(turned);
        for (uint32_t i = 0; i < kShadowCascades; ++i) {
            INFO("turned " << degrees << " degrees, cascade " << i);
            CHECK(after[i].radius == Approx(before[i].radius).epsilon(1e-6));
            CHECK(after[i].texelSize == Approx(before[i].texelSize).epsilon(1e-6));
        }
    }
}
