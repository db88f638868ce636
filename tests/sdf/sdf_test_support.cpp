#include "sdf_test_support.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>


namespace bricklight::sdftest {

double pointTriangleDistance(const glm::dvec3& p, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) {
    // Ericson, Real-Time Collision Detection 5.1.5: the closest point by Voronoi regions.
    const glm::dvec3 ab = b - a, ac = c - a, ap = p - a;
    const double d1 = glm::dot(ab, ap), d2 = glm::dot(ac, ap);
    if (d1 <= 0 && d2 <= 0) return glm::length(p - a);
    const glm::dvec3 bp = p - b;
    const double d3 = glm::dot(ab, bp), d4 = glm::dot(ac, bp);
    if (d3 >= 0 && d4 <= d3) return glm::length(p - b);
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0 && d1 >= 0 && d3 <= 0) {
        const double v = d1 / (d1 - d3);
        return glm::length(p - (a + v * ab));
    }
    const glm::dvec3 cp = p - c;
    const double d5 = glm::dot(ab, cp), d6 = glm::dot(ac, cp);
    if (d6 >= 0 && d5 <= d6) return glm::length(p - c);
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0 && d2 >= 0 && d6 <= 0) {
        const double w = d2 / (d2 - d6);
        return glm::length(p - (a + w * ac));
    }
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
        const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return glm::length(p - (b + w * (c - b)));
    }
    const double denom = va + vb + vc;
    if (!(std::fabs(denom) > 0)) {  // degenerate: the nearest of the edges
        auto seg = [&](const glm::dvec3& x, const glm::dvec3& y) {
            const glm::dvec3 e = y - x;
            const double ee = glm::dot(e, e);
            const double t = ee > 0 ? std::clamp(glm::dot(p - x, e) / ee, 0.0, 1.0) : 0.0;
            return glm::length(p - (x + t * e));
        };
        return std::min({seg(a, b), seg(b, c), seg(c, a)});
    }
    const double v = vb / denom, w = vc / denom;
    return glm::length(p - (a + ab * v + ac * w));
}

Reference::Reference(const scenes::SceneGeometry& scene, double cellSize) : cell_(cellSize) {
    for (const auto& inst : scene.instances) {
        const auto& m = scene.meshes[inst.mesh];
        const glm::dmat4 t(inst.transform);
        for (uint32_t i : m.indices)
            tris_.push_back(glm::dvec3(t * glm::dvec4(m.positions[3 * i], m.positions[3 * i + 1], m.positions[3 * i + 2], 1.0)));
    }
    lo_ = glm::dvec3(INFINITY);
    hi_ = glm::dvec3(-INFINITY);
    for (const auto& p : tris_) {
        lo_ = glm::min(lo_, p);
        hi_ = glm::max(hi_, p);
    }
    lo_ -= cell_;
    hi_ += cell_;
    dims_ = glm::max(glm::ivec3(glm::ceil((hi_ - lo_) / cell_)), glm::ivec3(1));
    const size_t cells = size_t(dims_.x) * dims_.y * dims_.z;
    std::vector<std::vector<uint32_t>> lists(cells);
    for (uint32_t t = 0; t < tris_.size() / 3; ++t) {
        glm::dvec3 a = glm::min(tris_[3 * t], glm::min(tris_[3 * t + 1], tris_[3 * t + 2]));
        glm::dvec3 b = glm::max(tris_[3 * t], glm::max(tris_[3 * t + 1], tris_[3 * t + 2]));
        glm::ivec3 c0 = glm::clamp(glm::ivec3(glm::floor((a - lo_) / cell_)), glm::ivec3(0), dims_ - 1);
        glm::ivec3 c1 = glm::clamp(glm::ivec3(glm::floor((b - lo_) / cell_)), glm::ivec3(0), dims_ - 1);
        for (int z = c0.z; z <= c1.z; ++z)
            for (int y = c0.y; y <= c1.y; ++y)
                for (int x = c0.x; x <= c1.x; ++x) lists[(size_t(z) * dims_.y + y) * dims_.x + x].push_back(t);
    }
    cellStart_.resize(cells + 1);
    for (size_t i = 0; i < cells; ++i) {
        cellStart_[i + 1] = cellStart_[i] + uint32_t(lists[i].size());
        cellTriangles_.insert(cellTriangles_.end(), lists[i].begin(), lists[i].end());
    }
}

double Reference::distance(const glm::dvec3& p, double limit) const {
    glm::ivec3 c0 = glm::clamp(glm::ivec3(glm::floor((p - limit - lo_) / cell_)), glm::ivec3(0), dims_ - 1);
    glm::ivec3 c1 = glm::clamp(glm::ivec3(glm::floor((p + limit - lo_) / cell_)), glm::ivec3(0), dims_ - 1);
    double best = limit;
    if (glm::any(glm::lessThan(p + limit, lo_)) || glm::any(glm::greaterThan(p - limit, hi_))) return best;
    for (int z = c0.z; z <= c1.z; ++z)
        for (int y = c0.y; y <= c1.y; ++y)
            for (int x = c0.x; x <= c1.x; ++x) {
                const size_t cell = (size_t(z) * dims_.y + y) * dims_.x + x;
                for (uint32_t k = cellStart_[cell]; k < cellStart_[cell + 1]; ++k) {
                    const uint32_t t = cellTriangles_[k];
                    best = std::min(best, pointTriangleDistance(p, tris_[3 * t], tris_[3 * t + 1], tris_[3 * t + 2]));
                }
            }
    return best;
}

bool Reference::intersect(const glm::dvec3& o, const glm::dvec3& d, double tMin, double tMax, double* tHit,
                          double* cosine) const {
    bool hit = false;
    double best = tMax;
    for (size_t t = 0; t < tris_.size() / 3; ++t) {
        const glm::dvec3 a = tris_[3 * t], e1 = tris_[3 * t + 1] - a, e2 = tris_[3 * t + 2] - a;
        const glm::dvec3 pv = glm::cross(d, e2);
        const double det = glm::dot(e1, pv);
        if (std::fabs(det) < 1e-300) continue;
        const double inv = 1.0 / det;
        const glm::dvec3 tv = o - a;
        const double u = glm::dot(tv, pv) * inv;
        if (u < 0 || u > 1) continue;
        const glm::dvec3 qv = glm::cross(tv, e1);
        const double v = glm::dot(d, qv) * inv;
        if (v < 0 || u + v > 1) continue;
        const double tt = glm::dot(e2, qv) * inv;
        if (tt > tMin && tt < best) {
            best = tt;
            hit = true;
            const glm::dvec3 n = glm::normalize(glm::cross(e1, e2));
            *cosine = std::fabs(glm::dot(n, d));
        }
    }
    *tHit = best;
    return hit;
}

std::vector<sdf::MeshHandle> createMeshes(sdf::SdfScene& scene, const scenes::SceneGeometry& geometry) {
    std::vector<sdf::MeshHandle> meshes;
    for (const auto& m : geometry.meshes)
        meshes.push_back(scene.createMesh({m.positions.data(), uint32_t(m.positions.size() / 3), m.indices.data(),
                                           uint32_t(m.indices.size()), m.name}));
    return meshes;
}

sdf::SceneDesc modelSceneDesc(const scenes::SceneGeometry& geometry, uint32_t cascades, TestDevice& td) {
    const glm::vec3 extent = geometry.boundsMax - geometry.boundsMin;
    sdf::SceneDesc desc;
    desc.cascadeCount = cascades;
    desc.finestVoxelSize = std::max(extent.x, std::max(extent.y, extent.z)) / 36.0f;
    desc.atlasBricksPerAxis = 32;
    auto messages = td.messages;
    desc.errorCallback = [messages](rhi::Severity, const std::string& m) { messages->push_back(m); };
    return desc;
}

LoadedScene loadIntoSdf(rhi::IDevice& device, const scenes::SceneGeometry& geometry, const sdf::SceneDesc& desc) {
    LoadedScene out;
    Error error;
    out.scene = sdf::SdfScene::create(device, desc, &error);
    if (!out.scene) return out;
    out.meshes = createMeshes(*out.scene, geometry);
    for (const auto& i : geometry.instances) {
        sdf::InstanceDesc d;
        d.mesh = out.meshes[i.mesh];
        d.transform = i.transform;
        d.alphaTested = geometry.meshes[i.mesh].alphaTested();
        d.material = sdf::SurfaceMaterial{geometry.meshes[i.mesh].albedo, geometry.meshes[i.mesh].emission};
        out.instances.push_back(out.scene->addInstance(d));
    }
    return out;
}

std::string testModelPath(const std::string& relative) {
    // BRICKLIGHT_TEST_MODELS moves the models (a GPU machine with nothing installed gets a copy).
    const char* root = std::getenv("BRICKLIGHT_TEST_MODELS");
    return std::string(root && *root ? root : "/usr/share/assimp/models") + "/" + relative;
}

FieldDifference compareFields(const sdf::FieldSnapshot& a, const sdf::FieldSnapshot& b) {
    FieldDifference r;
    for (uint32_t c = 0; c < a.cascades.size() && c < b.cascades.size(); ++c)
        for (int z = 0; z < 64; ++z)
            for (int y = 0; y < 64; ++y)
                for (int x = 0; x < 64; ++x) {
                    const glm::ivec3 v(x, y, z);
                    const uint32_t sa = a.voxelState(c, v), sb = b.voxelState(c, v);
                    r.voxelsCompared++;
                    const bool ba = sa < 0xFFFFFFF0u, bb = sb < 0xFFFFFFF0u;
                    if (ba != bb || (!ba && sa != sb)) {
                        if (!r.stateMismatches)
                            r.firstMismatch = "cascade " + std::to_string(c) + " voxel (" + std::to_string(x) + "," +
                                              std::to_string(y) + "," + std::to_string(z) + "): " + std::to_string(sa) +
                                              " vs " + std::to_string(sb);
                        r.stateMismatches++;
                        continue;
                    }
                    if (!ba) continue;
                    for (int i = 0; i < 512; ++i) {
                        const glm::ivec3 bx(i & 7, (i >> 3) & 7, i >> 6);
                        const int d = std::abs(int(a.brixel(sa, bx)) - int(b.brixel(sb, bx)));
                        if (d && r.firstMismatch.empty()) {
                            auto baseOf = [&](const sdf::FieldSnapshot& f) {
                                const sdf::FieldSnapshot::Cascade& fc = f.cascades[c];
                                const glm::ivec3 p = (fc.origin + v) & glm::ivec3(63);
                                return fc.baseMap.empty() ? 0u : fc.baseMap[size_t((p.z * 64 + p.y) * 64 + p.x)];
                            };
                            r.firstMismatch = "cascade " + std::to_string(c) + " voxel (" + std::to_string(x) + "," + std::to_string(y) + "," +
                                              std::to_string(z) + ") brixel " + std::to_string(i) + ": " + std::to_string(a.brixel(sa, bx)) +
                                              " vs " + std::to_string(b.brixel(sb, bx)) + ", bases " + std::to_string(baseOf(a)) + " / " +
                                              std::to_string(baseOf(b));
                        }
                        if (d) r.brixelsDiffering++;
                        r.maxBrixelDifference = std::max<uint32_t>(r.maxBrixelDifference, uint32_t(d));
                    }
                }
    return r;
}

}  // namespace bricklight::sdftest
