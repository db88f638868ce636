// The shadow tests' scene: a ground plane at y = 0 seen straight down from y = 10 by an orthographic camera over
// x −8..8, z −4..4 (row 0 at z = −4), and a plate hovering over it, as the G-buffer and the sun's shadow map of an
// application would hold them. The classifier's and the denoiser's tests build it at their own sizes.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "bricklight/rhi.h"

namespace bricklight::testing {

struct PlateSceneDesc {
    uint32_t width = 0, height = 0;  // the G-buffer
    uint32_t skyFromColumn = 0;      // columns from this one on are sky (depth 1)
    bool awayCorner = false;         // rows height−4.. of columns 0..7 face away from the sun (normal −y)
    uint32_t mapWidth = 0, mapHeight = 0;  // the sun's shadow map over the same x, z
    float mapTop = 20.0f;            // the map's depth 0 (y); depth 1 at y = 0
    float plateTop = 2.0f;           // the plate's upper face: what the map holds over it
    glm::vec2 plateMin{-2.0f, -1.0f}, plateMax{2.0f, 1.0f};  // the plate's extent in x, z
};

struct PlateScene {
    uint32_t width = 0, height = 0, mapWidth = 0, mapHeight = 0;
    glm::mat4 view{1.0f}, projection{1.0f};
    std::vector<float> depth;        // width × height, 1 = sky
    std::vector<glm::vec4> normals;  // stored = world normal (unpack scale 1, offset 0)
    std::vector<glm::vec2> ground;   // each pixel's ground point (x, z)
    std::vector<float> shadowMap;    // mapWidth × mapHeight
    glm::mat4 worldToShadow{1.0f};
};

inline PlateScene makePlateScene(const PlateSceneDesc& d) {
    PlateScene s;
    s.width = d.width;
    s.height = d.height;
    s.mapWidth = d.mapWidth;
    s.mapHeight = d.mapHeight;
    s.view = glm::lookAtRH(glm::vec3(0.0f, 10.0f, 0.0f), glm::vec3(0.0f), glm::vec3(0.0f, 0.0f, -1.0f));
    s.projection = glm::orthoRH_ZO(-8.0f, 8.0f, -4.0f, 4.0f, 0.1f, 20.0f);
    s.projection[1][1] = -s.projection[1][1];  // NDC y −1 at the top row (the library's convention)
    const glm::mat4 viewProjection = s.projection * s.view;
    for (uint32_t y = 0; y < d.height; ++y)
        for (uint32_t x = 0; x < d.width; ++x) {
            const glm::vec2 ndc((float(x) + 0.5f) / d.width * 2.0f - 1.0f, (float(y) + 0.5f) / d.height * 2.0f - 1.0f);
            const glm::vec4 w = glm::inverse(viewProjection) * glm::vec4(ndc, 0.5f, 1.0f);
            const glm::vec2 g(w.x / w.w, w.z / w.w);
            const glm::vec4 clip = viewProjection * glm::vec4(g.x, 0.0f, g.y, 1.0f);
            s.ground.push_back(g);
            s.depth.push_back(x >= d.skyFromColumn ? 1.0f : clip.z / clip.w);
            const bool away = d.awayCorner && x < 8 && y + 4 >= d.height;
            s.normals.push_back(away ? glm::vec4(0.0f, -1.0f, 0.0f, 0.0f) : glm::vec4(0.0f, 1.0f, 0.0f, 0.0f));
        }
    // The sun's map: u over x −8..8, v over z −4..4, depth 0 at y = mapTop and 1 at y = 0.
    s.worldToShadow = glm::mat4(0.0f);
    s.worldToShadow[0][0] = 1.0f / 16.0f;       // u = x / 16 + 0.5
    s.worldToShadow[2][1] = 1.0f / 8.0f;        // v = z / 8 + 0.5
    s.worldToShadow[1][2] = -1.0f / d.mapTop;   // depth = (top − y) / top
    s.worldToShadow[3] = glm::vec4(0.5f, 0.5f, 1.0f, 1.0f);
    for (uint32_t v = 0; v < d.mapHeight; ++v)
        for (uint32_t u = 0; u < d.mapWidth; ++u) {
            const float x = (float(u) + 0.5f) / d.mapWidth * 16.0f - 8.0f, z = (float(v) + 0.5f) / d.mapHeight * 8.0f - 4.0f;
            const bool plate = x > d.plateMin.x && x < d.plateMax.x && z > d.plateMin.y && z < d.plateMax.y;
            s.shadowMap.push_back(plate ? (d.mapTop - d.plateTop) / d.mapTop : 1.0f);
        }
    return s;
}

// The scene as sampled textures: depth (R32_FLOAT), normals (RGBA32_FLOAT) and the shadow map (R32_FLOAT); null
// handles where the device refuses one.
struct PlateTextures {
    rhi::TextureHandle depth, normals, shadowMap;
};

inline PlateTextures uploadPlateScene(rhi::IDevice& device, const PlateScene& s) {
    PlateTextures t;
    rhi::TextureDesc d;
    d.width = s.width;
    d.height = s.height;
    d.format = rhi::Format::R32_FLOAT;
    d.usage = rhi::TextureUsage::Sampled;
    d.debugName = "test depth";
    t.depth = device.createTexture(d, s.depth.data());
    d.format = rhi::Format::RGBA32_FLOAT;
    d.debugName = "test normals";
    t.normals = device.createTexture(d, s.normals.data());
    d.width = s.mapWidth;
    d.height = s.mapHeight;
    d.format = rhi::Format::R32_FLOAT;
    d.debugName = "test shadow map";
    t.shadowMap = device.createTexture(d, s.shadowMap.data());
    return t;
}

}  // namespace bricklight::testing
