// A bounding volume hierarchy over world-space triangles, built on the CPU (binned SAH) and flattened for
// the GPU path tracer: nodes in depth-first order, the left child right after its parent.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

namespace bricklight::render {

struct BvhNode {           // 32 bytes, two vec4 on the GPU
    glm::vec3 min;
    uint32_t rightOrFirst;  // inner: index of the right child; leaf: first triangle
    glm::vec3 max;
    uint32_t count;         // 0: inner node; else the leaf's triangle count
};
static_assert(sizeof(BvhNode) == 32);

struct Bvh {
    std::vector<BvhNode> nodes;
    std::vector<uint32_t> order;  // triangle index of each leaf slot
    uint32_t depth = 0;
};

// `positions` holds 3 vertices per triangle.
Bvh buildBvh(const std::vector<glm::vec3>& positions);

}  // namespace bricklight::render
