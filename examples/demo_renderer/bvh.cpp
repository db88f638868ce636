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
    double area() const {  // in double: a box spanning +-3e38 overflows float
        const glm::dvec3 e = glm::max(glm::dvec3(max) - glm::dvec3(min), glm::dvec3(0.0));
        return 2.0 * (e.x * e.y + e.y * e.z + e.z * e.x);
    }
};

struct Builder {
    const std::vector<glm::vec3>& positions;
    std::vector<Box> boxes;
    std::vector<glm::dvec3> centres;
    Bvh bvh;

    // Splits deeper than this are median splits: each halves its triangles, so the tree stays within the
    // GPU traversal stack (48) for up to 2^16 times more triangles than any device buffer holds, whatever
    // the centres (binned SAH on adversarial ones, e.g. exponentially spaced, peels one triangle a level).
    static constexpr uint32_t kSahDepth = 24;
    static constexpr uint32_t kMaxLeaf = 4;  // a leaf of more triangles is split even if SAH would not

    uint32_t build(uint32_t first, uint32_t count, uint32_t depth) {
        bvh.depth = std::max(bvh.depth, depth);
        Box box;
        glm::dvec3 lo(DBL_MAX), hi(-DBL_MAX);  // the centres' bounds, in double: finite floats never overflow it
        for (uint32_t i = first; i < first + count; ++i) {
            box.grow(boxes[bvh.order[i]]);
            lo = glm::min(lo, centres[bvh.order[i]]);
            hi = glm::max(hi, centres[bvh.order[i]]);
        }
        const uint32_t index = uint32_t(bvh.nodes.size());
        bvh.nodes.push_back({box.min, first, box.max, count});
        if (count <= 2) return index;
        const glm::dvec3 extent = hi - lo;
        const int axis = extent.x >= extent.y && extent.x >= extent.z ? 0 : (extent.y >= extent.z ? 1 : 2);
        uint32_t leftCount = 0;
        if (depth < kSahDepth && extent[axis] > 0.0) {
            const int split = sahSplit(first, count, axis, lo[axis], extent[axis], box);
            if (split == 0) return index;  // a leaf is cheapest
            if (split > 0) {
                auto mid = std::partition(bvh.order.begin() + first, bvh.order.begin() + first + count, [&](uint32_t tri) {
                    return binOf(tri, axis, lo[axis], extent[axis]) < split;
                });
                leftCount = uint32_t(mid - (bvh.order.begin() + first));
            }
        }
        if (leftCount == 0 || leftCount == count) {
            if (count <= kMaxLeaf && depth < kSahDepth) return index;
            // Median split: half the triangles by centre along the axis (by index where all centres are equal).
            leftCount = count / 2;
            std::nth_element(bvh.order.begin() + first, bvh.order.begin() + first + leftCount, bvh.order.begin() + first + count,
                             [&](uint32_t a, uint32_t b) { return centres[a][axis] < centres[b][axis]; });
        }
        build(first, leftCount, depth + 1);
        const uint32_t right = build(first + leftCount, count - leftCount, depth + 1);
        bvh.nodes[index].rightOrFirst = right;
        bvh.nodes[index].count = 0;
        return index;
    }

    static constexpr int kBins = 16;
    int binOf(uint32_t tri, int axis, double lo, double extent) const {
        const double t = (centres[tri][axis] - lo) / extent;  // in [0, 1] for finite centres
        return t >= 1.0 ? kBins - 1 : t > 0.0 ? int(t * kBins) : 0;
    }

    // Binned SAH over `axis`: the first bin of the right side (1..kBins-1), 0 when a leaf is cheaper, -1
    // when no split separates the triangles.
    int sahSplit(uint32_t first, uint32_t count, int axis, double lo, double extent, const Box& box) {
        Box bins[kBins];
        uint32_t counts[kBins] = {};
        for (uint32_t i = first; i < first + count; ++i) {
            const int b = binOf(bvh.order[i], axis, lo, extent);
            bins[b].grow(boxes[bvh.order[i]]);
            counts[b]++;
        }
        double best = DBL_MAX;
        int split = -1;
        for (int s = 1; s < kBins; ++s) {
            Box l, r;
            uint32_t nl = 0, nr = 0;
            for (int b = 0; b < s; ++b) l.grow(bins[b]), nl += counts[b];
            for (int b = s; b < kBins; ++b) r.grow(bins[b]), nr += counts[b];
            if (!nl || !nr) continue;
            const double cost = l.area() * double(nl) + r.area() * double(nr);
            if (cost < best) best = cost, split = s;
        }
        if (split > 0 && count <= kMaxLeaf && best >= box.area() * double(count)) return 0;
        return split;
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
        b.centres[t] = (glm::dvec3(b.boxes[t].min) + glm::dvec3(b.boxes[t].max)) * 0.5;
        b.bvh.order[t] = t;
    }
    if (n) b.build(0, n, 1);
    return std::move(b.bvh);
}

}  // namespace bricklight::render
