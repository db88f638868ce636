// The BVH builder on hostile but finite geometry: no undefined behaviour (float to int conversions of
// overflowing extents), every triangle in exactly one leaf, leaves bounding their triangles, and a depth
// the GPU traversal stack (48) holds.
#include <catch2/catch.hpp>

#include <cfloat>
#include <cmath>

#include "bvh.h"

using namespace bricklight::render;

namespace {

void requireValid(const Bvh& bvh, const std::vector<glm::vec3>& positions) {
    const uint32_t n = uint32_t(positions.size() / 3);
    REQUIRE(bvh.order.size() == n);
    CHECK(bvh.depth <= 48);
    std::vector<int> seen(n, 0);
    for (const BvhNode& node : bvh.nodes) {
        if (node.count == 0) continue;
        REQUIRE(uint64_t(node.rightOrFirst) + node.count <= n);
        for (uint32_t i = node.rightOrFirst; i < node.rightOrFirst + node.count; ++i) {
            const uint32_t t = bvh.order[i];
            REQUIRE(t < n);
            ++seen[t];
            for (int k = 0; k < 3; ++k) {
                const glm::vec3& p = positions[3 * t + size_t(k)];
                CHECK(glm::all(glm::lessThanEqual(node.min, p)));
                CHECK(glm::all(glm::lessThanEqual(p, node.max)));
            }
        }
    }
    for (uint32_t t = 0; t < n; ++t) REQUIRE(seen[t] == 1);
}

}  // namespace

TEST_CASE("the BVH holds triangles at the ends of the float range", "[bvh][cpu]") {
    // The case that crashed: the centres' extent overflowed float and the bin index became INT_MIN.
    const std::vector<glm::vec3> positions = {
        {-3e38f, 0, 0}, {3e38f, 0, 0}, {0, 3e38f, 0},  {-3e38f, -1, 0}, {3e38f, -1, 1},
        {0, -3e38f, 1}, {-FLT_MAX, 2, 5}, {FLT_MAX, 2, 6}, {0, FLT_MAX, -7}, {1, 1, 1}, {2, 2, 2}, {3, 1, 2}};
    requireValid(buildBvh(positions), positions);
}

TEST_CASE("the BVH stays shallow on centres that defeat SAH", "[bvh][cpu]") {
    // Exponentially spaced centres: every SAH split peels off one triangle, which went as deep as the
    // triangle count before the median fallback.
    std::vector<glm::vec3> positions;
    for (int i = 0; i < 120; ++i) {
        const float x = std::ldexp(1.0f, i);
        positions.insert(positions.end(), {{x, 0, 0}, {x, 1, 0}, {x, 0, 1}});
    }
    const Bvh bvh = buildBvh(positions);
    requireValid(bvh, positions);
    INFO("depth " << bvh.depth);
    CHECK(bvh.depth <= 32);
}

TEST_CASE("the BVH splits triangles whose centres all coincide", "[bvh][cpu]") {
    // 20000 copies of one triangle: no axis separates them, yet no leaf may hold them all (every ray
    // would test 20000 triangles).
    std::vector<glm::vec3> positions;
    for (int i = 0; i < 20000; ++i) positions.insert(positions.end(), {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
    const Bvh bvh = buildBvh(positions);
    requireValid(bvh, positions);
    uint32_t largest = 0;
    for (const BvhNode& node : bvh.nodes) largest = std::max(largest, node.count);
    CHECK(largest <= 4);
    CHECK(bvh.depth <= 20);
}
