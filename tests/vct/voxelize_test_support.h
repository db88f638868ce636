// Voxelizing triangle lists in tests: a mesh on the device drawn through Clipmap::voxelizationState with the
// test vertex shader (tests/vct/shaders/voxelize_mesh.vert), read-backs of the volumes, and scenes.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/vct.h"
#include "test_device.h"

namespace bricklight::testing {

struct Triangle {
    glm::vec3 p[3];
    glm::vec3 normal;  // the shading normal of all three vertices
};

// The tests' small clip-map: `levels` levels of 32³ voxels, the finest 1 unit wide.
vct::ClipmapDesc testClipmapDesc(uint32_t levels, vct::EmittanceMode mode = vct::EmittanceMode::Anisotropic);

// The 12 triangles of an axis-aligned box, normals outward, each face split along its diagonal.
std::vector<Triangle> boxTriangles(const glm::vec3& lo, const glm::vec3& hi);

class VoxelizeHarness {
public:
    VoxelizeHarness(TestDevice& td, const vct::ClipmapDesc& desc);
    ~VoxelizeHarness();
    vct::Clipmap& clipmap() { return *clipmap_; }
    // Draws the triangles with material.fragmentShader, or else the opacity-only shader (radiance null) or the
    // emissive test shader; `constants` are added to the draw (they must outlive the call).
    void draw(const std::vector<Triangle>& triangles, const vct::VoxelMaterial& material, const glm::vec3* radiance,
              const std::vector<rhi::ConstantsBinding>& constants = {});
    // The atlas read back (bricklight/vct_layout.glsl) and unpacked level by level: opacity words (8 bits per axis)
    // in texel order (level-major, then z, y, x of the toroidal texel), and radiance in channel-major order:
    // channel (direction × 3 + colour) of every texel, then the next. Radiance only after finishVoxelization()
    // (until then a direction's word is its light entry).
    std::vector<uint32_t> opacity();
    std::vector<float> emittance();
    uint32_t opacityAt(const std::vector<uint32_t>& volume, uint32_t level, glm::ivec3 voxel) const;
    size_t texelIndex(uint32_t level, glm::ivec3 voxel) const;
    // Where channel `word` of a voxel lies in emittance().
    size_t wordIndex(uint32_t level, glm::ivec3 voxel, uint32_t word) const;
    rhi::ShaderHandle emissiveShader() const { return emissive_; }

private:
    TestDevice& td_;
    std::unique_ptr<vct::Clipmap> clipmap_;
    rhi::ShaderHandle vertex_, emissive_;
    std::vector<rhi::BufferHandle> buffers_;
};

// Cones traced through a clip-map by the test shader vct_tests/trace_cones.comp (bricklight/cone_trace.glsl).
struct ConeIn {
    glm::vec4 origin, direction;  // w: cone factor; w: ambient range
};
struct ConeOut {
    glm::vec3 radiance;
    float ambient, finalOpacity, samples;
};
// RGB9E5 bits as radiance (bricklight/rgb9e5.glsl's layout).
glm::vec3 decodeRgb9e5(uint32_t bits);
// Channels of emittance() (texelCount texels per channel) that differ by more than `relative` of the larger of the
// two voxels' largest channel of that direction (plus 1e-6). `where` gets the first such channel's index.
size_t radianceDifferences(const std::vector<float>& a, const std::vector<float>& b, size_t texelCount, float relative,
                           size_t* where = nullptr);
// The bound the tests state between runs, backends and voxelizers: none. The light sums are exact integers whatever
// the order of the adds, and their RGB9E5 encoding is canonical (bricklight/rgb9e5.glsl), so the words agree bit
// for bit.
constexpr float kLightDifferenceBound = 0.0f;

std::vector<ConeOut> traceCones(TestDevice& td, VoxelizeHarness& h, const std::vector<ConeIn>& cones);

}  // namespace bricklight::testing
