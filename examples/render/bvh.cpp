#include "bvh.h"

#include <algorithm>
#include <cfloat>

namespace bricklight::render {

namespace {

struct Box {
    glm::vec3 min{FLT_MAX}, max{-FLT_MAX};
    void grow(const glm::vec3& p) {
        min = glm::min(min, p);
        max = glm::max(max, p);
    }
    void grow(const Box& b) {
        min = glm::min(min, b.min);
        max = glm::max(max, b.max);
    }
    float area() const {
        const glm::vec3 e = glm::max(max - min, glm::vec3(0.0f));
        return 2.0f * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

struct Builder {
    const std::vector<glm::vec3>& positions;
    std::vector<Box> boxes;
    std::vector<glm::vec3> centres;
    Bvh bvh;

    uint32_t build(uint32_t first, uint32_t count, uint32_t depth) {
        bvh.depth = std::max(bvh.depth, depth);
        Box box, centreBox;
        for (uint32_t i = first; i < first + count; ++i) {
            box.grow(boxes[bvh.order[i]]);
            centreBox.grow(centres[bvh.order[i]]);
        }
        const uint32_t index = uint32_t(bvh.nodes.size());
        bvh.nodes.push_back({box.min, first, box.max, count});
        if (count <= 2) return index;
        // Binned SAH over the longest axis of the centres.
        const glm::vec3 extent = centreBox.max - centreBox.min;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        if (extent[axis] <= 0.0f) return index;  // all centres equal: a leaf
        constexpr int kBins = 16;
        Box bins[kBins];
        uint32_t counts[kBins] = {};
        auto binOf = [&](uint32_t tri) {
            const float t = (centres[tri][axis] - centreBox.min[axis]) / extent[axis];
            return std::min(kBins - 1, int(t * kBins));
        };
        for (uint32_t i = first; i < first + count; ++i) {
            const int b = binOf(bvh.order[i]);
            bins[b].grow(boxes[bvh.order[i]]);
            counts[b]++;
        }
        float best = FLT_MAX;
        int split = -1;
        for (int s = 1; s < kBins; ++s) {
            Box l, r;
            uint32_t nl = 0, nr = 0;
            for (int b = 0; b < s; ++b) l.grow(bins[b]), nl += counts[b];
            for (int b = s; b < kBins; ++b) r.grow(bins[b]), nr += counts[b];
            if (!nl || !nr) continue;
            const float cost = l.area() * float(nl) + r.area() * float(nr);
            if (cost < best) best = cost, split = s;
        }
        if (split < 0 || (count <= 4 && best >= box.area() * float(count))) return index;
        auto mid = std::partition(bvh.order.begin() + first, bvh.order.begin() + first + count,
                                  [&](uint32_t tri) { return binOf(tri) < split; });
        const uint32_t leftCount = uint32_t(mid - (bvh.order.begin() + first));
        build(first, leftCount, depth + 1);
        const uint32_t right = build(first + leftCount, count - leftCount, depth + 1);
        bvh.nodes[index].rightOrFirst = right;
        bvh.nodes[index].count = 0;
        return index;
    }
};

}  // namespace

Bvh buildBvh(const std::vector<glm::vec3>& positions) {
    Builder b{positions, {}, {}, {}};
    const uint32_t n = uint32_t(positions.size() / 3);
    b.boxes.resize(n);
    b.centres.resize(n);
    b.bvh.order.resize(n);
    for (uint32_t t = 0; t < n; ++t) {
        for (int k = 0; k < 3; ++k) b.boxes[t].grow(positions[3 * t + k]);
        b.centres[t] = (b.boxes[t].min + b.boxes[t].max) * 0.5f;
        b.bvh.order[t] = t;
    }
    if (n) b.build(0, n, 1);
    return std::move(b.bvh);
}

}  // namespace bricklight::render
