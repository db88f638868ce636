// Bricklight reflection classifier (FidelityFX Classifier-class, hybrid reflections): sorts the glossy pixels of
// the screen into a screen-space ray list and a distance-field (SDF) ray list, tile by tile (8×8 pixels), from
// their roughness and from how well screen-space rays did in each tile over the previous frames (hit/miss
// counters carried along the motion), and traces the screen-space list through a depth pyramid; the rays it
// misses join the SDF list. docs/reflections.md.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>

#include <glm/glm.hpp>

#include "bricklight/reflections/ray_list.h"
#include "bricklight/errors.h"
#include "bricklight/memory_use.h"
#include "bricklight/gbuffer/inputs.h"
#include "bricklight/rhi.h"

namespace bricklight::reflections {

constexpr uint32_t kReflectionTileSize = 8;            // 8×8 pixels a tile, sixteen to a 256-thread group
constexpr uint32_t kReflectionScreenGroupRays = 32;    // screen-space trace: 32 list entries a group, one tile each
// The SDF list's group size is the ray list contract's (bricklight/reflections/ray_list.h); the old name stays for a
// version.
[[deprecated("use bricklight::kReflectionRaysPerGroup")]] constexpr uint32_t kReflectionSdfGroupRays = kReflectionRaysPerGroup;
constexpr uint32_t kReflectionHelperEntry = kReflectionSkippedEntry;  // padding in the screen-space list: no ray
constexpr size_t kReflectionParamsBytes = 512;         // the passes' parameter block (internal)

// The arguments buffer (rayCounts()): dispatchIndirect arguments at these byte offsets, then the counts (the rest of
// readCounts()'s figures are per tile: tile info and tile statistics).
constexpr uint64_t kReflectionArgsScreenTrace = 0;  // {padded entries / 32, 1, 1}: traceScreenSpace()
constexpr uint64_t kReflectionArgsSdfTrace = 12;    // {⌈SDF rays / 64⌉, 1, 1}: the SDF pass, 64 rays a group
constexpr uint64_t kReflectionArgsDenoise = 24;     // {denoiser tiles, 1, 1}: one 8×8 group per listed tile
constexpr uint64_t kReflectionCountScreenEntries = 36;  // uint: screen-space list length, helpers included
constexpr uint64_t kReflectionCountSdfRays = 44;        // uint: SDF list length (the SDF pass's ray count)
constexpr uint64_t kReflectionCountDenoiseTiles = 48;   // uint: denoiser list length
constexpr uint32_t kReflectionCountWords = 24;

// Ray lists hold one uint per ray (bricklight/reflections/ray_list.h: packReflectionRay, reflectionRayPixel).
using bricklight::packReflectionRay;
using bricklight::reflectionRayPixel;

// A tile's class. The checkerboard is the transition between the two, used where this frame's decision and the
// last frame's differ: rays of pixels with ((x ^ y) & 1) == 0 go screen-space first, the others to the SDF
// (with samplesPerQuad 1 or 2 the checkerboard is of 2×2 quads, (x/2 ^ y/2) & 1, so that both halves get rays).
enum class ReflectionTileClass : uint32_t { ScreenSpaceFirst, Checkerboard, SdfOnly };

struct ReflectionClassifyDesc {
    gbuffer::Camera camera;                    // bricklight/gbuffer/inputs.h
    bricklight::gbuffer::Inputs gbuffer;       // depth, normals, roughness, motion
    float roughnessThreshold = 0.4f;     // perceptual: pixels at least this rough get no ray
    float sdfRoughnessThreshold = 0.4f;  // perceptual: pixels at least this rough never go to the SDF list directly
    uint32_t samplesPerQuad = 4;  // rays per 2×2 quad: 1 (x, y even), 2 (x + y even), 4
    bool useHitCounter = true;    // false: every tile ScreenSpaceFirst
    bool useScreenSpace = true;   // false: every tile SdfOnly (rays too rough for the SDF get none)
    bool useSdf = true;           // false: every tile ScreenSpaceFirst, and the trace's misses are not listed
    float hybridMissWeight = 0.5f;   // a tile goes screen-space first when rnd ≤ spawnRate + hits − weight·misses
    float hybridSpawnRate = 0.02f;   // the chance that a tile without hits tries screen space again
    uint32_t frameIndex = 0;         // seeds the dice and the rays' directions
};

struct ReflectionTraceDesc {
    // Min/max depth pyramid of classify()'s depth (DepthPyramid::texture(), or the engine's own of that layout):
    // RG32_FLOAT, sampled, the classifier's size at mip 0, any number of mips.
    rhi::TextureHandle depthPyramid;
    // The previous frame's lit image (this frame's is not ready before the composite): sampled, float or unorm,
    // any size (read bilinearly by UV through the previous camera).
    rhi::TextureHandle previousLit;
    // RGBA16_FLOAT with Storage usage, the classifier's size. After the trace: rgb the reflected radiance and a = 1
    // where a screen-space ray (or the quad neighbour it was copied to) resolved; a = 0 and rgb 0 everywhere
    // else (no ray, a ray for the SDF pass, a miss): the whole texture is written.
    rhi::TextureHandle output;
    uint32_t maxIterations = 96;        // hierarchical steps a ray may take (1..1024)
    // How far behind a surface's depth still counts as the surface, as a fraction of its distance from the camera
    // (scale-free: the same for a scene in millimetres and one in metres).
    float thickness = 0.05f;
    float edgeFade = 0.05f;             // confidence fades to 0 within this fraction of the screen from its edges
    float confidenceThreshold = 0.9f;   // hits less confident than this are misses (to the SDF list)
};

struct ReflectionClassifyCounts {
    uint32_t screenSpaceFirstTiles = 0, checkerboardTiles = 0, sdfOnlyTiles = 0;  // on-screen tiles by class
    uint32_t screenRays = 0;      // in the screen-space list
    uint32_t screenEntries = 0;   // its length, helpers included (a multiple of 32)
    uint32_t sdfRays = 0;         // in the SDF list: the classifier's, plus the trace's misses once traced
    uint32_t screenMisses = 0;    // of those, the trace's misses (0 before traceScreenSpace())
    uint32_t screenHits = 0;      // screen-space rays that resolved (0 before traceScreenSpace())
    uint32_t denoiseTiles = 0;    // tiles with any ray
    uint32_t rayPixels = 0;       // pixels with a ray of their own
    uint32_t glossyPixels = 0;    // on-screen surface pixels below roughnessThreshold
    uint32_t surfacePixels = 0;   // on-screen pixels that are not sky
};

// What debugView() shows, per tile: its class (green screen-space first, yellow checkerboard, red SdfOnly;
// dimmed without rays); its rays (green screen-space, red SDF, each /64); the hit counter (green new hits, red
// new misses, blue previous hits, each /64).
enum class ReflectionDebugMode : uint32_t { TileClass, RaysPerTile, HitCounter };

struct ReflectionClassifierDesc {
    uint32_t width = 0, height = 0;  // the G-buffer's size in pixels, 1..16384 a side
};

//   resource                 format                               holds
//   screen-space ray list    buffer, ⌈W/8⌉·⌈H/8⌉·64 uints          packed rays, each tile's padded to a multiple of
//                                                                 32 with kReflectionHelperEntry
//   SDF ray list             buffer, W·H uints                     packed rays (unpadded), the trace's misses after
//                                                                 the classifier's
//   denoiser tile list       buffer, ⌈W/8⌉·⌈H/8⌉ uints             top-left pixel y << 16 | x of each tile with a ray
//   ray counts A, B          buffer, 24 uints, IndirectArgs        the offsets above; classify() adds to one and
//                                                                 zeroes the other, which the next classify() adds to
//   hit counters ×2          R32_UINT ⌈W/8⌉ × ⌈H/8⌉, ping-pong     per tile: new hits (bits 0..7), new misses (8..15),
//                                                                 previous hits (16..23), previous misses (24..31)
//   tile info                R32_UINT ⌈W/8⌉ × ⌈H/8⌉               class (bits 0..1), screen rays (8..15), SDF rays
//                                                                 (16..23, misses included after the trace), screen
//                                                                 rays resolved (24..31, after the trace)
//   tile statistics          R32_UINT ⌈W/8⌉ × ⌈H/8⌉               surface pixels (0..7), glossy pixels (8..15), the
//                                                                 classifier's SDF rays (16..23), pixels with a ray
//                                                                 (24..31): readCounts() sums them on the CPU
class ReflectionClassifier {
public:
    // Null with *error for a zero or too large size (1..16384 a side), or a device that cannot create the resources.
    static std::unique_ptr<ReflectionClassifier> create(rhi::IDevice& device, const ReflectionClassifierDesc& desc, Error* error = nullptr);
    ~ReflectionClassifier();
    ReflectionClassifier(const ReflectionClassifier&) = delete;
    ReflectionClassifier& operator=(const ReflectionClassifier&) = delete;

    // Records the classification: the lists, the counts, the arguments, this frame's hit counter (the history is
    // the last frame's, read along the motion). False with *error, recording nothing and changing no state, for
    // missing, mis-sized or wrongly formatted inputs, non-finite or singular cameras, or bad parameters.
    bool classify(const ReflectionClassifyDesc& desc, Error* error = nullptr);
    // Records the screen-space trace of the last classify()'s list (whose depth, normals and roughness must still
    // be live): dispatchIndirect at kReflectionArgsScreenTrace, 32 threads a group; output as ReflectionTraceDesc
    // says; misses (with useSdf) appended to the SDF list with their copy flags and the SDF arguments updated;
    // each tile's new-hit / new-miss counter raised by the pixels its rays resolved / missed. Once per classify().
    bool traceScreenSpace(const ReflectionTraceDesc& desc, Error* error = nullptr);
    // Per tile into `output` (RGBA8_UNORM with Storage usage, the classifier's size), after classify() (and the
    // trace, for its rays and counters).
    bool debugView(rhi::TextureHandle output, ReflectionDebugMode mode, Error* error = nullptr);

    rhi::BufferHandle screenRayList() const { return screenList_; }
    rhi::BufferHandle sdfRayList() const { return sdfList_; }
    rhi::BufferHandle denoiseTileList() const { return denoiseList_; }
    // The arguments and counts (offsets above) of the last classify(): two buffers alternate (each classify() zeroes the
    // other for the next), so ask for it after each classify() rather than keeping it.
    rhi::BufferHandle rayCounts() const { return counts_[countIndex_]; }
    // The counters the last classify() wrote and the trace added to: the next classify() reads them as history.
    // Before the first classify(), zero (tests may write their own here to seed the history).
    rhi::TextureHandle hitCounter() const { return hitCounters_[current_]; }
    rhi::TextureHandle tileInfo() const { return tileInfo_; }
    uint32_t width() const { return width_; }
    uint32_t height() const { return height_; }
    uint32_t tilesX() const { return (width_ + kReflectionTileSize - 1) / kReflectionTileSize; }
    uint32_t tilesY() const { return (height_ + kReflectionTileSize - 1) / kReflectionTileSize; }
    uint32_t screenListCapacity() const { return tilesX() * tilesY() * 64; }
    uint32_t sdfListCapacity() const { return width_ * height_; }
    ReflectionClassifyCounts readCounts();  // waits for the GPU and sums the tiles' statistics (tests and tools)

    MemoryUse memoryUse() const;  // its textures and buffers on the device

private:
    explicit ReflectionClassifier(rhi::IDevice& device) : device_(device) {}
    bool writeParams(const void* bytes, size_t offset, size_t size);
    bool recordArgs();
    rhi::IDevice& device_;
    uint32_t width_ = 0, height_ = 0;
    rhi::ShaderHandle classify_, args_, trace_, debug_, clear_;
    rhi::BufferHandle screenList_, sdfList_, denoiseList_, params_;
    rhi::BufferHandle counts_[2];  // classify() adds to one and zeroes the other for the next classify()
    uint32_t countIndex_ = 1;      // counts_[countIndex_]: the last classify()'s
    rhi::TextureHandle hitCounters_[2], tileInfo_, tileStats_, noMotion_;
    rhi::SamplerHandle point_, linear_;
    uint32_t current_ = 0;  // which hit counter the last classify() wrote
    rhi::TextureHandle depth_, normals_, roughness_;  // the last classify()'s, for the trace
    bool classified_ = false, traced_ = false;
    std::array<uint8_t, kReflectionParamsBytes> lastParams_{};  // what params_ holds
    bool paramsWritten_ = false;
};

}  // namespace bricklight::reflections
