// Bricklight voxel cone tracing (VXGI-class) — in progress. This first part is the clip-map's geometry: a
// stack of levels of equal resolution, each twice the voxel size of the one below, centred on an anchor the
// application moves, addressed toroidally so that moving the anchor revoxelizes only the slabs that entered.
// Voxelization through draw records, emittance, cone tracing and the GPU resources come next (docs/vct.md
// will describe them; the issue "Voxel cone tracing GI and voxel AO on a clip-map" lists the plan).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

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

}  // namespace bricklight::vct
