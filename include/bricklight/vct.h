// Bricklight voxel cone tracing (VXGI-class) — in progress. So far the clip-map: a stack of levels of equal
// resolution, each twice the voxel size of the one below, centred on an anchor the application moves,
// addressed toroidally so that moving the anchor revoxelizes only the slabs that entered; and its opacity
// volume on the device, cleared where levels scroll. Voxelization through draw records, emittance and cone
// tracing come next (docs/vct.md grows with them).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"
#include "bricklight/sdf.h"  // MemoryUse

namespace bricklight::vct {

constexpr uint32_t kMinLevels = 2, kMaxLevels = 8;

struct ClipmapDesc {
    uint32_t levels = 5;             // stack levels, kMinLevels..kMaxLevels (VXGI 2.0 in UE4: 128³ × 5)
    uint32_t resolution = 128;       // voxels per axis of every level: 32, 64, 128 or 256
    float finestVoxelSize = 0.08f;   // world units; level L's voxels are finestVoxelSize × 2^L
    // Coarser mips of the last level above the stack (each halves its resolution); 0: log2(resolution) − 2,
    // down to 4³, as VXGI does.
    uint32_t mipLevels = 0;
};

// False with *error naming the field and the problem for a description no clip-map can have.
bool checkClipmapDesc(const ClipmapDesc& desc, std::string* error);
// The mip count a description asks for (resolving 0).
uint32_t clipmapMipLevels(const ClipmapDesc& desc);

// A box of voxels of one level in world voxel coordinates (voxel v of level L covers
// [v, v + 1) × finestVoxelSize × 2^L in world units): min inclusive, max exclusive.
struct VoxelBox {
    glm::ivec3 min{0}, max{0};
    uint64_t voxelCount() const;
};

// Where a level lies after an anchor move, and what of it must be voxelized because it entered the level.
struct LevelUpdate {
    uint32_t level = 0;
    glm::ivec3 origin{0};          // world voxel coordinates of the level's lowest corner
    std::vector<VoxelBox> entered;  // disjoint; the whole level when it moved by a level's width or more
};

// The levels' placement around the anchor (CPU side; the voxelization passes take it as constants).
// Each level's origin is an even number of its own voxels, so that every voxel of level L+1 is exactly 2³
// voxels of level L (downsampling reads whole voxels), and the levels nest: level L lies inside level L+1.
class ClipmapPlacement {
public:
    // Null with *error for a bad description. No level is placed until the first moveAnchor().
    static std::optional<ClipmapPlacement> create(const ClipmapDesc& desc, std::string* error);
    // Centres every level on `anchor` (snapped to its grid; non-finite anchors are refused with *error and
    // change nothing). Returns each level's new origin and the boxes that entered it: everything on the
    // first call or after invalidate(); then only the slabs the move uncovered (nothing if the snapped
    // origin did not change).
    std::optional<std::vector<LevelUpdate>> moveAnchor(const glm::vec3& anchor, std::string* error);
    // The next moveAnchor() revoxelizes every level in full.
    void invalidate() { placed_ = false; }

    const ClipmapDesc& desc() const { return desc_; }
    float voxelSize(uint32_t level) const;  // world units
    glm::ivec3 origin(uint32_t level) const { return origins_[level]; }
    bool contains(uint32_t level, const glm::ivec3& voxel) const;
    // The texel of a level's volume that holds a world voxel: each axis modulo the resolution (positive),
    // so a voxel keeps its texel while the level scrolls over it.
    glm::ivec3 toroidalTexel(const glm::ivec3& voxel) const;
    // The world voxel of `level` that holds a point.
    glm::ivec3 voxelAt(uint32_t level, const glm::vec3& point) const;

private:
    explicit ClipmapPlacement(const ClipmapDesc& desc) : desc_(desc) {}
    ClipmapDesc desc_;
    std::vector<glm::ivec3> origins_;
    bool placed_ = false;
};

using MemoryUse = sdf::MemoryUse;

// The clip-map's volumes on a device, kept in step with the placement. So far the opacity volume; the
// emittance volumes and the passes that fill them come next.
//
//   volume        format     size                                   holds
//   opacity       R32_UINT   resolution² × (resolution × levels)   per voxel; level L in z slices
//                                                                   [L·resolution, (L+1)·resolution),
//                                                                   a world voxel at its coordinates
//                                                                   modulo resolution (toroidal)
class Clipmap {
public:
    // Null with *error for a bad description or a device that cannot create the volumes.
    static std::unique_ptr<Clipmap> create(rhi::IDevice& device, const ClipmapDesc& desc, std::string* error);
    ~Clipmap();
    Clipmap(const Clipmap&) = delete;
    Clipmap& operator=(const Clipmap&) = delete;

    // Moves the anchor (ClipmapPlacement::moveAnchor) and records a clear of every box that entered a
    // level (shaders/vct/clear_boxes.comp), in place in the toroidal volumes. A refused anchor changes and
    // records nothing.
    std::optional<std::vector<LevelUpdate>> update(const glm::vec3& anchor, std::string* error);
    void invalidate() { placement_.invalidate(); }

    const ClipmapPlacement& placement() const { return placement_; }
    rhi::TextureHandle opacityVolume() const { return opacity_; }
    MemoryUse memoryUse() const;

private:
    Clipmap(rhi::IDevice& device, const ClipmapPlacement& placement) : device_(device), placement_(placement) {}
    rhi::IDevice& device_;
    ClipmapPlacement placement_;
    rhi::ShaderHandle clearBoxes_;
    rhi::TextureHandle opacity_;
};

}  // namespace bricklight::vct
