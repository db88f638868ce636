// Bricklight stateless RHI: complete records (DispatchState, DrawCallState) consumed by an IDevice that
// the engine implements. Nothing persists between calls except resources; every call carries the shader,
// every binding (with its view inline), declared access and inline constant bytes. See docs/rhi.md.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <string_view>
#include <vector>

#include "bricklight/shader_blob.h"

namespace bricklight::rhi {

// ---------------------------------------------------------------------------------------------------
// Handles: 32-bit ids issued by the device, never reused for the lifetime of the device (so a destroyed
// handle can always be told from a live one). Id 0 is the null handle.
// ---------------------------------------------------------------------------------------------------
template <typename Tag>
struct Handle {
    uint32_t id = 0;
    explicit operator bool() const { return id != 0; }
    friend bool operator==(Handle a, Handle b) { return a.id == b.id; }
    friend bool operator!=(Handle a, Handle b) { return a.id != b.id; }
};
using TextureHandle = Handle<struct TextureTag>;
using BufferHandle = Handle<struct BufferTag>;
using SamplerHandle = Handle<struct SamplerTag>;
using ShaderHandle = Handle<struct ShaderTag>;

// ---------------------------------------------------------------------------------------------------
// Formats. Every backend reports per-format support in Capabilities; R11G11B10_FLOAT and RGB9E5_FLOAT are
// sampled-only by contract (write their bits into an R32_UINT texture and sample it through a view in the packed
// format, or use RGBA16_FLOAT for storage).
// ---------------------------------------------------------------------------------------------------
enum class Format : uint8_t {
    Unknown = 0,
    R8_UNORM,
    R8_UINT,
    R16_FLOAT,
    R16_UINT,
    R32_FLOAT,
    R32_UINT,
    R32_SINT,
    RG8_UNORM,
    RG16_FLOAT,
    RG32_FLOAT,
    RG32_UINT,
    RGBA8_UNORM,
    RGBA8_SRGB,
    RGBA16_FLOAT,
    RGBA32_FLOAT,
    RGBA32_UINT,
    R11G11B10_FLOAT,
    RGB9E5_FLOAT,  // shared exponent: 9-bit mantissas (R bits 0–8, G 9–17, B 18–26), exponent bits 27–31, bias 15
    D32_FLOAT,
    Count
};

struct FormatInfo {
    const char* name;
    uint8_t bytesPerTexel;
    uint8_t channels;
    enum class Kind : uint8_t { None, Unorm, Uint, Sint, Float, Srgb, PackedFloat, Depth } kind;
};
const FormatInfo& formatInfo(Format format);
const char* formatName(Format format);
Format formatFromName(std::string_view name);  // Unknown if not a format name

// ---------------------------------------------------------------------------------------------------
// Resource descriptions
// ---------------------------------------------------------------------------------------------------
enum class TextureDimension : uint8_t { Texture2D, Texture2DArray, Texture3D, TextureCube };
const char* textureDimensionName(TextureDimension dimension);

namespace TextureUsage {
enum : uint32_t {
    Sampled = 1u << 0,       // read through a sampler (BL_TEXTURE)
    Storage = 1u << 1,       // image load/store/atomics (BL_IMAGE)
    RenderTarget = 1u << 2,  // colour attachment of a draw
    DepthTarget = 1u << 3,   // depth attachment of a draw
};
}

struct TextureDesc {
    TextureDimension dimension = TextureDimension::Texture2D;
    Format format = Format::RGBA8_UNORM;
    uint32_t width = 1;
    uint32_t height = 1;
    uint32_t depthOrLayers = 1;  // depth for 3D, layers for arrays, 6 for cubes
    uint32_t mipLevels = 1;
    uint32_t usage = TextureUsage::Sampled;
    std::string debugName;
};

namespace BufferUsage {
enum : uint32_t {
    ShaderRead = 1u << 0,    // BL_READ_BUFFER
    ShaderWrite = 1u << 1,   // BL_STORAGE_BUFFER (read-write, atomics)
    IndirectArgs = 1u << 2,  // argument source of dispatchIndirect / drawIndirect
    Vertex = 1u << 3,
    Index = 1u << 4,
};
}

struct BufferDesc {
    uint64_t size = 0;
    // Non-zero: a structured buffer of elements of this many bytes (views must be multiples of it);
    // zero: a raw buffer (views must be multiples of 4 bytes).
    uint32_t structStride = 0;
    uint32_t usage = BufferUsage::ShaderRead | BufferUsage::ShaderWrite;
    std::string debugName;
};

enum class Filter : uint8_t { Nearest, Linear };
enum class AddressMode : uint8_t { Repeat, MirroredRepeat, ClampToEdge, ClampToBorder };
enum class BorderColor : uint8_t { TransparentBlack, OpaqueBlack, OpaqueWhite };
enum class CompareOp : uint8_t { Never, Less, Equal, LessOrEqual, Greater, NotEqual, GreaterOrEqual, Always };

struct SamplerDesc {
    Filter minFilter = Filter::Linear;
    Filter magFilter = Filter::Linear;
    Filter mipFilter = Filter::Linear;
    AddressMode addressU = AddressMode::ClampToEdge;
    AddressMode addressV = AddressMode::ClampToEdge;
    AddressMode addressW = AddressMode::ClampToEdge;
    BorderColor borderColor = BorderColor::TransparentBlack;
    float minLod = 0.0f;
    float maxLod = 1000.0f;
    float mipLodBias = 0.0f;
    float maxAnisotropy = 1.0f;  // 1 = off
    bool compareEnable = false;  // depth comparison sampling
    CompareOp compareOp = CompareOp::Less;
    std::string debugName;
};

struct ShaderDesc {
    const ShaderBlob* blob = nullptr;  // embedded GLSL + SPIR-V + reflection (see shader_blob.h)
    std::string debugName;             // defaults to blob->name
};

// ---------------------------------------------------------------------------------------------------
// Records. Plain structs with fixed capacities: cheap to copy, comparable, hashable, printable.
// ---------------------------------------------------------------------------------------------------
template <typename T, size_t N>
struct FixedVector {
    T items[N] = {};
    uint8_t count = 0;
    static constexpr size_t capacity = N;
    // Returns false (and stores nothing) when full; the validation wrapper reports overflow.
    bool push(const T& value) {
        if (count >= N) return false;
        items[count++] = value;
        return true;
    }
    const T* begin() const { return items; }
    const T* end() const { return items + count; }
    T* begin() { return items; }
    T* end() { return items + count; }
    size_t size() const { return count; }
    bool empty() const { return count == 0; }
    const T& operator[](size_t i) const { return items[i]; }
    T& operator[](size_t i) { return items[i]; }
};

enum class Access : uint8_t { Read, Write, ReadWrite, Atomic };
const char* accessName(Access access);
inline bool accessWrites(Access a) { return a != Access::Read; }

// A texture view, described inline. mipCount/layerCount of 0 mean "all remaining".
struct TextureView {
    TextureHandle texture;
    Format format = Format::Unknown;  // Unknown = the texture's format; else a same-size reinterpretation
    uint8_t baseMip = 0;
    uint8_t mipCount = 0;
    uint16_t baseLayer = 0;
    uint16_t layerCount = 0;
};

// A buffer range; size 0 means "to the end of the buffer".
struct BufferRange {
    uint64_t offset = 0;
    uint64_t size = 0;
};

// Binding classes, one GLSL macro each (include/bricklight/bindings.glsl).
enum class BindingClass : uint8_t { Constants, Texture, ReadBuffer, StorageBuffer, StorageImage };
const char* bindingClassName(BindingClass c);

struct ConstantsBinding {       // BL_CONSTANTS(slot): std140 uniform block, bytes copied at call time
    uint8_t slot = 0;
    const void* data = nullptr;  // only needs to live for the duration of the call
    uint32_t size = 0;
};
struct TextureBinding {          // BL_TEXTURE(slot): sampler2D/3D/Array/Cube, always read
    uint8_t slot = 0;
    TextureView view;
    SamplerHandle sampler;
};
struct ReadBufferBinding {       // BL_READ_BUFFER(slot): readonly std430 buffer
    uint8_t slot = 0;
    BufferHandle buffer;
    BufferRange range;
};
struct StorageBufferBinding {    // BL_STORAGE_BUFFER(slot): read-write std430 buffer
    uint8_t slot = 0;
    BufferHandle buffer;
    BufferRange range;
    Access access = Access::ReadWrite;
};
struct StorageImageBinding {     // BL_IMAGE(slot, fmt): image load/store/atomics on one mip (all layers)
    uint8_t slot = 0;
    TextureView view;            // mipCount must be 1 (or 0 with baseMip the last level)
    Access access = Access::ReadWrite;
};

constexpr uint32_t kMaxConstantsSlots = 4;
constexpr uint32_t kMaxTextureSlots = 16;
constexpr uint32_t kMaxReadBufferSlots = 8;
constexpr uint32_t kMaxStorageBufferSlots = 8;
constexpr uint32_t kMaxStorageImageSlots = 8;
constexpr uint32_t kMaxConstantsBytes = 256;
// Markers nest at most this deep (GL promises 64 debug groups; deeper nesting is nearly always an endMarker
// missing). The validation wrapper and our backends refuse a deeper beginMarker with an error, and ignore the
// endMarker that closes it.
constexpr uint32_t kMaxMarkerDepth = 32;

struct Bindings {
    FixedVector<ConstantsBinding, kMaxConstantsSlots> constants;
    FixedVector<TextureBinding, kMaxTextureSlots> textures;
    FixedVector<ReadBufferBinding, kMaxReadBufferSlots> readBuffers;
    FixedVector<StorageBufferBinding, kMaxStorageBufferSlots> storageBuffers;
    FixedVector<StorageImageBinding, kMaxStorageImageSlots> storageImages;
};
// Adds every binding of `from` to `to` (a library's record plus the application's own resources); false if one
// did not fit, which the validation wrapper also reports.
inline bool appendBindings(Bindings& to, const Bindings& from) {
    bool ok = true;
    for (const auto& b : from.constants) ok = to.constants.push(b) && ok;
    for (const auto& b : from.textures) ok = to.textures.push(b) && ok;
    for (const auto& b : from.readBuffers) ok = to.readBuffers.push(b) && ok;
    for (const auto& b : from.storageBuffers) ok = to.storageBuffers.push(b) && ok;
    for (const auto& b : from.storageImages) ok = to.storageImages.push(b) && ok;
    return ok;
}

namespace DispatchFlags {
enum : uint32_t {
    // The writes of this call are order-independent with the previous writer of the same resources
    // (e.g. both accumulate with atomics): the backend places no write-after-write barrier between them.
    NoBarrierWithPreviousWriter = 1u << 0,
};
}

struct DispatchState {
    ShaderHandle shader;   // a compute shader
    Bindings bindings;
    uint32_t flags = 0;
    const char* label = nullptr;  // names the record in messages, markers and recordings
};

enum class PrimitiveTopology : uint8_t { TriangleList, TriangleStrip, LineList, PointList };
enum class IndexFormat : uint8_t { U16, U32 };
enum class CullMode : uint8_t { None, Front, Back };
enum class FrontFace : uint8_t { CounterClockwise, Clockwise };
enum class LoadOp : uint8_t { Load, Clear, DontCare };
enum class BlendFactor : uint8_t {
    Zero, One, SrcColor, OneMinusSrcColor, DstColor, OneMinusDstColor,
    SrcAlpha, OneMinusSrcAlpha, DstAlpha, OneMinusDstAlpha
};
enum class BlendOp : uint8_t { Add, Subtract, ReverseSubtract, Min, Max };

// 3-component float positions are common; VertexFormat lets them through without a texture format.
enum class VertexFormat : uint8_t { Float1, Float2, Float3, Float4, UByte4Norm, UInt1, Half4 };
struct VertexInput {
    uint8_t location = 0;
    VertexFormat format = VertexFormat::Float3;
    uint8_t bufferIndex = 0;
    uint32_t offset = 0;
};
struct VertexBufferBinding {
    BufferHandle buffer;
    uint64_t offset = 0;
    uint32_t stride = 0;
    bool perInstance = false;
};
struct IndexBufferBinding {
    BufferHandle buffer;
    uint64_t offset = 0;
    IndexFormat format = IndexFormat::U32;
};

struct BlendState {
    bool enable = false;
    BlendFactor srcColor = BlendFactor::One;
    BlendFactor dstColor = BlendFactor::Zero;
    BlendOp colorOp = BlendOp::Add;
    BlendFactor srcAlpha = BlendFactor::One;
    BlendFactor dstAlpha = BlendFactor::Zero;
    BlendOp alphaOp = BlendOp::Add;
    uint8_t writeMask = 0xF;  // RGBA bits
};

struct ColorTarget {
    TextureView view;  // one mip, one layer (baseMip/baseLayer)
    LoadOp load = LoadOp::Load;
    float clearColor[4] = {0, 0, 0, 0};
    BlendState blend;
};
struct DepthTarget {
    TextureView view;  // D32_FLOAT, one mip, one layer
    LoadOp load = LoadOp::Load;
    float clearDepth = 1.0f;
};
struct DepthState {
    bool testEnable = false;
    bool writeEnable = false;
    CompareOp compare = CompareOp::Less;
};
struct RasterState {
    CullMode cull = CullMode::None;
    FrontFace frontFace = FrontFace::CounterClockwise;
    bool depthClamp = false;
    float depthBiasConstant = 0.0f;
    float depthBiasSlope = 0.0f;
};
struct Viewport {
    float x = 0, y = 0, width = 0, height = 0;  // width 0 = the size of the targets
    float minDepth = 0.0f, maxDepth = 1.0f;
};
struct ScissorRect {
    int32_t x = 0, y = 0;
    uint32_t width = 0, height = 0;  // width 0 = no scissor (the whole viewport)
};

constexpr uint32_t kMaxColorTargets = 8;
constexpr uint32_t kMaxVertexInputs = 8;
constexpr uint32_t kMaxVertexBuffers = 4;

struct DrawCallState {
    ShaderHandle vertexShader;
    ShaderHandle geometryShader;  // optional
    ShaderHandle fragmentShader;  // optional (depth-only)
    FixedVector<VertexInput, kMaxVertexInputs> vertexInputs;
    FixedVector<VertexBufferBinding, kMaxVertexBuffers> vertexBuffers;
    IndexBufferBinding indexBuffer;  // used by drawIndexed / indexed drawIndirect
    PrimitiveTopology topology = PrimitiveTopology::TriangleList;
    FixedVector<ColorTarget, kMaxColorTargets> colorTargets;
    DepthTarget depthTarget;  // view.texture null = none
    DepthState depth;
    RasterState raster;
    Viewport viewport;
    ScissorRect scissor;
    Bindings bindings;  // visible to every stage of the draw (GL has one namespace per class)
    const char* label = nullptr;
};

struct DrawArgs {
    uint32_t vertexCount = 0;
    uint32_t instanceCount = 1;
    uint32_t firstVertex = 0;
    uint32_t firstInstance = 0;
};
struct DrawIndexedArgs {
    uint32_t indexCount = 0;
    uint32_t instanceCount = 1;
    uint32_t firstIndex = 0;
    int32_t vertexOffset = 0;
    uint32_t firstInstance = 0;
};
// Indirect argument layouts in the args buffer (match Vulkan and GL exactly).
struct DispatchIndirectArgs { uint32_t x, y, z; };
static_assert(sizeof(DrawArgs) == 16 && sizeof(DrawIndexedArgs) == 20 && sizeof(DispatchIndirectArgs) == 12);

// ---------------------------------------------------------------------------------------------------
// Transfers
// ---------------------------------------------------------------------------------------------------
// One mip level of a texture; for 3D textures `layer` is ignored and all slices are covered; for arrays
// and cubes `layerCount` layers starting at `layer` (0 = all remaining). Data is tightly packed,
// layer-major then row-major (rows top to bottom).
struct TextureSubresource {
    uint32_t mip = 0;
    uint32_t layer = 0;
    uint32_t layerCount = 0;
};

union ClearValue {
    float f[4];
    uint32_t u[4];
};

// ---------------------------------------------------------------------------------------------------
// Capabilities and diagnostics
// ---------------------------------------------------------------------------------------------------
namespace FormatSupport {
enum : uint32_t {
    Sampled = 1u << 0,
    Filterable = 1u << 1,
    Storage = 1u << 2,
    StorageAtomic = 1u << 3,
    RenderTarget = 1u << 4,
    Blendable = 1u << 5,
    DepthTarget = 1u << 6,
};
}

struct Limits {
    uint32_t maxTextureSize2D = 0;
    uint32_t maxTextureSize3D = 0;
    uint32_t maxTextureArrayLayers = 0;
    uint32_t maxComputeGroupCount[3] = {};
    uint32_t maxComputeGroupSize[3] = {};
    uint32_t maxComputeGroupInvocations = 0;
    uint32_t maxComputeSharedMemoryBytes = 0;
    uint64_t maxStorageBufferRange = 0;
    uint32_t maxColorTargets = 0;
    uint32_t minStorageBufferOffsetAlignment = 0;
    uint32_t minUniformBufferOffsetAlignment = 0;
};

struct Capabilities {
    std::string backendName;  // "vulkan", "gl", "null", or the integrator's
    std::string deviceName;   // driver/device string
    Limits limits;
    uint32_t formatSupport[static_cast<size_t>(Format::Count)] = {};  // FormatSupport bits
    bool geometryShader = false;
    bool timestamps = false;
    bool supports(Format f, uint32_t bits) const {
        return (formatSupport[static_cast<size_t>(f)] & bits) == bits;
    }
};

enum class Severity : uint8_t { Info, Warning, Error };
// Messages name the call, the object (by debug name) and the field, e.g.
// "dispatch 'blur': storageImages[0] (slot 2): texture 'hdr' format R11G11B10_FLOAT is not storage-capable".
using ErrorCallback = std::function<void(Severity, const std::string& message)>;

// State of a non-blocking read-back (IDevice::requestReadback / pollReadback).
enum class ReadbackStatus : uint8_t { Pending, Ready, Failed };

struct MarkerTiming {
    std::string label;  // nested markers are joined with '/'
    double milliseconds = 0.0;
    uint64_t frame = 0;
};

// An engine-owned native object handed to wrapNative*. The meaning of the fields belongs to the backend:
// Vulkan: object = VkImage / VkBuffer, aux = VkImageLayout the image is in (and is returned to).
// GL: object = texture / buffer name, aux unused.
struct NativeObject {
    uint64_t object = 0;
    uint64_t aux = 0;
};

// ---------------------------------------------------------------------------------------------------
// IDevice: what an engine implements. Single-threaded: one thread calls a device at a time.
// Every call that fails reports through the error callback and changes nothing.
// ---------------------------------------------------------------------------------------------------
class IDevice {
public:
    virtual ~IDevice() = default;

    virtual const Capabilities& capabilities() const = 0;
    virtual void setErrorCallback(ErrorCallback callback) = 0;

    // Resources. initialData (optional) is tightly packed: all mips of layer 0, then layer 1... for
    // textures; `size` bytes for buffers. Without it a buffer reads as zero (a texture's contents are
    // undefined until written or cleared). Failure returns a null handle.
    virtual TextureHandle createTexture(const TextureDesc& desc, const void* initialData = nullptr) = 0;
    virtual BufferHandle createBuffer(const BufferDesc& desc, const void* initialData = nullptr) = 0;
    virtual SamplerHandle createSampler(const SamplerDesc& desc) = 0;
    virtual ShaderHandle createShader(const ShaderDesc& desc) = 0;
    virtual TextureHandle wrapNativeTexture(const TextureDesc& desc, NativeObject native) = 0;
    virtual BufferHandle wrapNativeBuffer(const BufferDesc& desc, NativeObject native) = 0;
    // Destruction is deferred by the backend until the GPU no longer uses the object; wrapped native
    // objects are forgotten, not freed.
    virtual void destroy(TextureHandle texture) = 0;
    virtual void destroy(BufferHandle buffer) = 0;
    virtual void destroy(SamplerHandle sampler) = 0;
    virtual void destroy(ShaderHandle shader) = 0;
    virtual const TextureDesc* describe(TextureHandle texture) const = 0;  // null if not live
    virtual const BufferDesc* describe(BufferHandle buffer) const = 0;

    // Transfers, ordered with the calls around them.
    virtual bool writeBuffer(BufferHandle buffer, uint64_t offset, const void* data, uint64_t size) = 0;
    virtual bool writeTexture(TextureHandle texture, TextureSubresource sub, const void* data) = 0;
    virtual bool copyBuffer(BufferHandle dst, uint64_t dstOffset, BufferHandle src, uint64_t srcOffset,
                            uint64_t size) = 0;
    // Copies one whole subresource between textures of the same format and mip size.
    virtual bool copyTexture(TextureHandle dst, TextureSubresource dstSub, TextureHandle src,
                             TextureSubresource srcSub) = 0;
    virtual bool clearBuffer(BufferHandle buffer, BufferRange range, uint32_t value) = 0;
    // Clears mips [baseMip, baseMip+mipCount) of all layers; float formats take value.f, integer formats
    // value.u, depth value.f[0].
    virtual bool clearTexture(TextureHandle texture, uint32_t baseMip, uint32_t mipCount, ClearValue value) = 0;
    // Blocking read-backs for tests and tools: wait for all prior work, copy into `out`.
    virtual bool readBuffer(BufferHandle buffer, uint64_t offset, uint64_t size, void* out) = 0;
    virtual bool readTexture(TextureHandle texture, TextureSubresource sub, void* out) = 0;
    // Non-blocking read-back, for statistics and GPU feedback in a normal frame: records a copy of the
    // range now, ordered with the calls around it, and returns a ticket (0 on failure). pollReadback
    // never waits: Pending until the GPU has finished the copy, then Ready once (the bytes are copied to
    // `out`, which must hold the requested size, and the ticket is forgotten); Failed for an unknown
    // ticket (no message). A read-back finishes at the latest when endFrame() recycles its frame, or
    // on waitIdle().
    virtual uint64_t requestReadback(BufferHandle buffer, uint64_t offset, uint64_t size) = 0;
    virtual ReadbackStatus pollReadback(uint64_t ticket, void* out) = 0;

    // Work.
    virtual bool dispatch(const DispatchState& state, uint32_t groupsX, uint32_t groupsY, uint32_t groupsZ) = 0;
    virtual bool dispatchIndirect(const DispatchState& state, BufferHandle args, uint64_t offset) = 0;
    virtual bool draw(const DrawCallState& state, const DrawArgs& args) = 0;
    virtual bool drawIndexed(const DrawCallState& state, const DrawIndexedArgs& args) = 0;
    // DrawArgs at `offset`, or DrawIndexedArgs when `indexed`.
    virtual bool drawIndirect(const DrawCallState& state, BufferHandle args, uint64_t offset, bool indexed) = 0;

    // Markers and GPU timing. Markers nest; with timing enabled each marker pair is timed on the GPU.
    virtual void beginMarker(const char* label) = 0;
    virtual void endMarker() = 0;
    virtual void setTimingEnabled(bool enabled) = 0;
    // Times only markers nested at most `depth` deep (1: the outermost; 0 is taken as 1; default: all).
    // The end of a timed marker waits for all the work before it, so timing inner markers keeps the calls
    // inside an outer marker from overlapping; time only the outer level to measure what overlap gains.
    virtual void setTimingDepth(uint32_t depth) = 0;
    // Returns the timings that the GPU has finished since the last call, without waiting.
    virtual std::vector<MarkerTiming> takeTimings() = 0;

    // Frame boundary: submits recorded work (standalone) and advances the frame counter used for
    // deferred destruction and timings. Never waits for the GPU unless too many frames are in flight.
    virtual void endFrame() = 0;
    // Waits for all submitted work.
    virtual void waitIdle() = 0;
};

// ---------------------------------------------------------------------------------------------------
// Helpers for building records.
// ---------------------------------------------------------------------------------------------------
inline TextureView wholeTexture(TextureHandle t) { return TextureView{t}; }
inline TextureView textureMip(TextureHandle t, uint8_t mip) {
    TextureView v{t};
    v.baseMip = mip;
    v.mipCount = 1;
    return v;
}
// A storage image binding of one mip of a texture.
inline StorageImageBinding storageImage(uint8_t slot, TextureHandle t, Access access, uint8_t mip = 0) {
    StorageImageBinding b;
    b.slot = slot;
    b.view = textureMip(t, mip);
    b.access = access;
    return b;
}
template <typename T>
ConstantsBinding constants(uint8_t slot, const T& value) {
    static_assert(sizeof(T) <= kMaxConstantsBytes, "constants larger than kMaxConstantsBytes");
    return ConstantsBinding{slot, &value, static_cast<uint32_t>(sizeof(T))};
}
// The binding points at `value` until the call records it: a temporary would be gone by then.
template <typename T>
ConstantsBinding constants(uint8_t slot, const T&& value) = delete;

// Mip dimensions of a texture (never below 1).
inline uint32_t mipExtent(uint32_t base, uint32_t mip) {
    const uint32_t e = mip < 32 ? base >> mip : 0;  // a shift by 32 or more is undefined
    return e ? e : 1;
}
// Bytes of one subresource as read/written by readTexture/writeTexture; 0 when the subresource lies outside
// the texture, the format has no size, or the count would not fit 64 bits (any description is safe).
uint64_t subresourceBytes(const TextureDesc& desc, TextureSubresource sub);
// Layers covered by a TextureSubresource (3D: 1; layerCount 0 = remaining layers).
uint32_t subresourceLayerCount(const TextureDesc& desc, TextureSubresource sub);
uint32_t textureLayerCount(const TextureDesc& desc);  // arrays/cubes: depthOrLayers; 2D/3D: 1
uint32_t textureDepth(const TextureDesc& desc, uint32_t mip);  // 3D: depth of that mip; else 1

}  // namespace bricklight::rhi
