#include "voxelize_test_support.h"

#include <algorithm>
#include <cmath>

#include <catch2/catch.hpp>

namespace bricklight::testing {

std::vector<Triangle> boxTriangles(const glm::vec3& lo, const glm::vec3& hi) {
    std::vector<Triangle> out;
    for (int axis = 0; axis < 3; ++axis)
        for (int side = 0; side < 2; ++side) {
            const int u = (axis + 1) % 3, v = (axis + 2) % 3;
            glm::vec3 n(0.0f);
            n[axis] = side ? 1.0f : -1.0f;
            auto corner = [&](int cu, int cv) {
                glm::vec3 p;
                p[axis] = side ? hi[axis] : lo[axis];
                p[u] = cu ? hi[u] : lo[u];
                p[v] = cv ? hi[v] : lo[v];
                return p;
            };
            out.push_back({{corner(0, 0), corner(1, 0), corner(1, 1)}, n});
            out.push_back({{corner(0, 0), corner(1, 1), corner(0, 1)}, n});
        }
    return out;
}

VoxelizeHarness::VoxelizeHarness(TestDevice& td, const vct::ClipmapDesc& desc) : td_(td) {
    Error error;
    clipmap_ = vct::Clipmap::create(*td.device, desc, &error);
    INFO(error.message);
    REQUIRE(clipmap_);
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct_tests/voxelize_mesh.vert");
    REQUIRE(sd.blob);
    vertex_ = td.device->createShader(sd);
    sd.blob = rhi::findShader("vct_tests/voxelize_emissive.frag");
    REQUIRE(sd.blob);
    emissive_ = td.device->createShader(sd);
    REQUIRE(vertex_);
    REQUIRE(emissive_);
}

VoxelizeHarness::~VoxelizeHarness() {
    for (rhi::BufferHandle b : buffers_) td_.device->destroy(b);
    td_.device->destroy(vertex_);
    td_.device->destroy(emissive_);
}

void VoxelizeHarness::draw(const std::vector<Triangle>& triangles, const vct::VoxelMaterial& base, const glm::vec3* radiance,
                           const std::vector<rhi::ConstantsBinding>& constants) {
    std::vector<float> vertices;
    for (const Triangle& t : triangles)
        for (const glm::vec3& p : t.p)
            vertices.insert(vertices.end(), {p.x, p.y, p.z, t.normal.x, t.normal.y, t.normal.z});
    rhi::BufferDesc bd;
    bd.size = vertices.size() * sizeof(float);
    bd.usage = rhi::BufferUsage::Vertex;
    bd.debugName = "voxelized mesh";
    const rhi::BufferHandle buffer = td_.device->createBuffer(bd, vertices.data());
    REQUIRE(buffer);
    buffers_.push_back(buffer);
    vct::VoxelMaterial material = base;
    if (!material.fragmentShader) material.fragmentShader = radiance ? emissive_ : rhi::ShaderHandle{};
    Error error;
    std::optional<rhi::DrawCallState> state = clipmap_->voxelizationState(material, &error);
    INFO(error.message);
    REQUIRE(state);
    state->vertexShader = vertex_;
    state->vertexInputs.push(rhi::VertexInput{0, rhi::VertexFormat::Float3, 0, 0});
    state->vertexInputs.push(rhi::VertexInput{1, rhi::VertexFormat::Float3, 0, 12});
    state->vertexBuffers.push(rhi::VertexBufferBinding{buffer, 0, 24, false});
    const glm::vec4 emission(radiance ? *radiance : glm::vec3(0.0f), 0.0f);
    if (radiance && material.fragmentShader == emissive_) state->bindings.constants.push(rhi::constants(0, emission));
    for (const rhi::ConstantsBinding& c : constants) state->bindings.constants.push(c);
    rhi::DrawArgs args;
    args.vertexCount = uint32_t(triangles.size() * 3);
    REQUIRE(td_.device->draw(*state, args));
}

namespace {

std::vector<uint32_t> readAtlas(TestDevice& td, const vct::Clipmap& clipmap) {
    const rhi::TextureDesc* d = td.device->describe(clipmap.atlas());
    REQUIRE(d);
    std::vector<uint32_t> words(size_t(d->width) * d->height * d->depthOrLayers);
    REQUIRE(td.device->readTexture(clipmap.atlas(), {}, words.data()));
    return words;
}

// The atlas word of a level's toroidal texel t in a region (vct_layout.glsl's vctTexel).
size_t atlasIndex(const vct::ClipmapDesc& d, uint32_t region, uint32_t level, glm::ivec3 t) {
    const uint32_t r = d.resolution, width = (1 + vct::emittanceDirections(d.emittance)) * (r + 2);
    const size_t x = region * (r + 2) + 1 + uint32_t(t.x), z = level * (r + 2) + 1 + uint32_t(t.z);
    return (z * r + uint32_t(t.y)) * width + x;
}

}  // namespace

glm::vec3 decodeRgb9e5(uint32_t v) {
    const float scale = std::ldexp(1.0f, int(v >> 27) - 24);
    return glm::vec3(float(v & 511u), float((v >> 9) & 511u), float((v >> 18) & 511u)) * scale;
}

size_t radianceDifferences(const std::vector<float>& a, const std::vector<float>& b, size_t texelCount, float relative, size_t* where) {
    REQUIRE(a.size() == b.size());
    REQUIRE(texelCount > 0);
    REQUIRE(a.size() % (3 * texelCount) == 0);
    size_t count = 0;
    for (size_t direction = 0; direction < a.size() / (3 * texelCount); ++direction)
        for (size_t t = 0; t < texelCount; ++t) {
            float largest = 0.0f;
            for (size_t c = 0; c < 3; ++c) {
                const size_t i = (direction * 3 + c) * texelCount + t;
                largest = std::max(largest, std::max(std::abs(a[i]), std::abs(b[i])));
            }
            for (size_t c = 0; c < 3; ++c) {
                const size_t i = (direction * 3 + c) * texelCount + t;
                if (std::abs(a[i] - b[i]) > relative * largest + 1e-6f) {
                    if (count == 0 && where) *where = i;
                    ++count;
                }
            }
        }
    return count;
}

std::vector<uint32_t> VoxelizeHarness::opacity() {
    const vct::ClipmapDesc& d = clipmap_->desc();
    const std::vector<uint32_t> atlas = readAtlas(td_, *clipmap_);
    const int r = int(d.resolution);
    std::vector<uint32_t> texels(size_t(r) * r * r * d.levels);
    for (uint32_t level = 0; level < d.levels; ++level)
        for (int z = 0; z < r; ++z)
            for (int y = 0; y < r; ++y)
                for (int x = 0; x < r; ++x)
                    texels[((size_t(level) * r + z) * r + y) * r + x] = atlas[atlasIndex(d, 0, level, {x, y, z})];
    return texels;
}

std::vector<float> VoxelizeHarness::emittance() {
    const vct::ClipmapDesc& d = clipmap_->desc();
    // No light lost to a full light pool (counted since the latest update, whatever setCountersEnabled says).
    const vct::VoxelizationCounters counters = clipmap_->readCounters();
    INFO(counters.lightEntriesClaimed << " of " << counters.lightEntriesAvailable << " light entries claimed");
    CHECK(counters.lightDropped == 0);
    const uint32_t directions = vct::emittanceDirections(d.emittance);
    const std::vector<uint32_t> atlas = readAtlas(td_, *clipmap_);
    const int r = int(d.resolution);
    const size_t texelCount = size_t(r) * r * r * d.levels;
    std::vector<float> channels(texelCount * directions * 3);
    for (uint32_t direction = 0; direction < directions; ++direction)
        for (uint32_t level = 0; level < d.levels; ++level)
            for (int z = 0; z < r; ++z)
                for (int y = 0; y < r; ++y)
                    for (int x = 0; x < r; ++x) {
                        const glm::vec3 radiance = decodeRgb9e5(atlas[atlasIndex(d, 1 + direction, level, {x, y, z})]);
                        const size_t texel = ((size_t(level) * r + z) * r + y) * r + x;
                        for (uint32_t c = 0; c < 3; ++c) channels[(direction * 3 + c) * texelCount + texel] = radiance[c];
                    }
    return channels;
}

size_t VoxelizeHarness::texelIndex(uint32_t level, glm::ivec3 voxel) const {
    const uint32_t r = clipmap_->desc().resolution;
    const glm::ivec3 t = clipmap_->placement().toroidalTexel(voxel);
    return (size_t(level * r + uint32_t(t.z)) * r + size_t(t.y)) * r + size_t(t.x);
}

size_t VoxelizeHarness::wordIndex(uint32_t level, glm::ivec3 voxel, uint32_t word) const {
    const vct::ClipmapDesc& d = clipmap_->desc();
    return size_t(word) * d.resolution * d.resolution * d.resolution * d.levels + texelIndex(level, voxel);
}

uint32_t VoxelizeHarness::opacityAt(const std::vector<uint32_t>& volume, uint32_t level, glm::ivec3 voxel) const {
    return volume[texelIndex(level, voxel)];
}

vct::ClipmapDesc testClipmapDesc(uint32_t levels, vct::EmittanceMode mode) {
    vct::ClipmapDesc d;
    d.levels = levels;
    d.resolution = 32;
    d.finestVoxelSize = 1.0f;
    d.emittance = mode;
    return d;
}

std::vector<ConeOut> traceCones(TestDevice& td, VoxelizeHarness& h, const std::vector<ConeIn>& cones) {
    rhi::ShaderDesc sd;
    sd.blob = rhi::findShader("vct_tests/trace_cones.comp");
    REQUIRE(sd.blob);
    rhi::ShaderHandle shader = td.device->createShader(sd);
    rhi::BufferDesc bd;
    bd.size = cones.size() * sizeof(ConeIn);
    bd.usage = rhi::BufferUsage::ShaderRead;
    bd.debugName = "cones";
    rhi::BufferHandle in = td.device->createBuffer(bd, cones.data());
    bd.size = cones.size() * 32;
    bd.usage = rhi::BufferUsage::ShaderWrite;
    bd.debugName = "cone results";
    rhi::BufferHandle out = td.device->createBuffer(bd);
    REQUIRE(shader);
    REQUIRE(in);
    REQUIRE(out);
    rhi::DispatchState s;
    s.shader = shader;
    s.label = "trace test cones";
    h.clipmap().traceBindings(s.bindings);
    s.bindings.readBuffers.push(rhi::ReadBufferBinding{0, in, {}});
    s.bindings.storageBuffers.push(rhi::StorageBufferBinding{0, out, {}, rhi::Access::Write});
    REQUIRE(td.device->dispatch(s, uint32_t(cones.size() + 63) / 64, 1, 1));
    std::vector<float> words(cones.size() * 8);
    REQUIRE(td.device->readBuffer(out, 0, words.size() * 4, words.data()));
    std::vector<ConeOut> results;
    for (size_t i = 0; i < cones.size(); ++i)
        results.push_back({glm::vec3(words[8 * i], words[8 * i + 1], words[8 * i + 2]), words[8 * i + 4], words[8 * i + 5], words[8 * i + 6]});
    td.device->destroy(shader);
    td.device->destroy(in);
    td.device->destroy(out);
    return results;
}

}  // namespace bricklight::testing
