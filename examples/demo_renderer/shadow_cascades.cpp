#include "shadow_cascades.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace bricklight::render {

std::array<float, kShadowCascades + 1> cascadeSplits(float nearPlane, float farPlane, float lambda) {
    std::array<float, kShadowCascades + 1> s{};
    const float logNear = std::max(nearPlane, farPlane * 1e-3f);
    for (uint32_t i = 0; i <= kShadowCascades; ++i) {
        const float t = float(i) / float(kShadowCascades);
        const float logSplit = logNear * std::pow(farPlane / logNear, t);
        const float uniformSplit = nearPlane + (farPlane - nearPlane) * t;
        s[i] = lambda * logSplit + (1.0f - lambda) * uniformSplit;
    }
    s[0] = nearPlane;
    s[kShadowCascades] = farPlane;
    return s;
}

glm::mat4 sunViewMatrix(const glm::vec3& sunDirection) {
    const glm::vec3 d = glm::normalize(sunDirection);
    const glm::vec3 up = std::fabs(d.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
    return glm::lookAtRH(glm::vec3(0.0f), -d, up);
}

std::array<ShadowCascade, kShadowCascades> fitCascades(const CascadeFitDesc& desc) {
    std::array<ShadowCascade, kShadowCascades> out{};
    const glm::mat4 light = sunViewMatrix(desc.sunDirection);
    // Light-space depth: every corner of the scene's bounds, so that casters outside a slice still cast.
    float zMin = 1e30f, zMax = -1e30f;
    for (int c = 0; c < 8; ++c) {
        const glm::vec3 p((c & 1) ? desc.sceneMax.x : desc.sceneMin.x, (c & 2) ? desc.sceneMax.y : desc.sceneMin.y,
                          (c & 4) ? desc.sceneMax.z : desc.sceneMin.z);
        const float z = (light * glm::vec4(p, 1.0f)).z;
        zMin = std::min(zMin, z);
        zMax = std::max(zMax, z);
    }
    const float margin = 1e-3f * std::max(zMax - zMin, 1e-3f);
    const float depthNear = -(zMax + margin), depthFar = -(zMin - margin);  // distances along −z (towards the scene)
    const std::array<float, kShadowCascades + 1> split = cascadeSplits(desc.nearPlane, desc.shadowDistance, desc.splitLambda);
    const float tanV = std::tan(glm::radians(desc.verticalFovDegrees) * 0.5f), tanH = tanV * desc.aspect;
    const float k2 = tanV * tanV + tanH * tanH;  // squared lateral reach of a corner per unit of view distance
    const glm::vec3 forward = glm::normalize(desc.forward);
    const uint32_t res = std::max(desc.resolution, 2 * kShadowBorderTexels + 2);
    for (uint32_t i = 0; i < kShadowCascades; ++i) {
        const float n = split[i], f = split[i + 1];
        // The smallest sphere through the slice's eight corners, centred on the view axis: a function of n, f
        // and the field of view only, so turning the camera does not change it.
        float c = 0.5f * (n + f) * (1.0f + k2), r;
        if (c >= f) {
            c = f;
            r = std::sqrt(k2) * f;
        } else {
            r = std::sqrt((f - c) * (f - c) + k2 * f * f);
        }
        ShadowCascade& sc = out[i];
        sc.splitNear = n;
        sc.splitFar = f;
        sc.radius = r;
        // res texels span 2r, one texel the snapping may take and the border on each side.
        sc.texelSize = 2.0f * r / float(res - 2 * kShadowBorderTexels - 1);
        const glm::vec3 centre = glm::vec3(light * glm::vec4(desc.eye + forward * c, 1.0f));
        sc.origin = (glm::floor((glm::vec2(centre) - r) / sc.texelSize) - float(kShadowBorderTexels)) * sc.texelSize;
        const float width = sc.texelSize * float(res);
        const glm::mat4 ortho = glm::orthoRH_ZO(sc.origin.x, sc.origin.x + width, sc.origin.y, sc.origin.y + width, depthNear, depthFar);
        sc.viewProjection = ortho * light;
        sc.depthRange = depthFar - depthNear;
    }
    return out;
}

}  // namespace bricklight::render
