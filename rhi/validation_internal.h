// Shared state of the validation wrapper: what it knows of live objects, and how it words messages.
#pragma once

#include <string>
#include <unordered_map>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::rhi::validation {

struct ShaderInfo {
    const ShaderBlob* blob = nullptr;
    std::string name;
};

// Live objects, keyed by handle id. Destroyed ids are removed, so a stale handle is simply unknown.
struct ObjectTable {
    std::unordered_map<uint32_t, TextureDesc> textures;
    std::unordered_map<uint32_t, BufferDesc> buffers;
    std::unordered_map<uint32_t, SamplerDesc> samplers;
    std::unordered_map<uint32_t, ShaderInfo> shaders;
    // Ids that were live once: lets a message say "destroyed" rather than "unknown".
    std::unordered_map<uint32_t, std::string> destroyedTextures, destroyedBuffers, destroyedSamplers,
        destroyedShaders;
};

// Collects the problems of one call; the call is forwarded only if `errors` stays empty.
struct Report {
    std::string call;  // e.g. "dispatch 'blur' (shader 'gi/blur.comp')"
    std::vector<std::string> errors;
    std::vector<std::string> warnings;
    void error(const std::string& what) { errors.push_back(call + ": " + what); }
    void warning(const std::string& what) { warnings.push_back(call + ": " + what); }
};

std::string quoted(const std::string& s);
std::string describeTexture(const ObjectTable& t, TextureHandle h);  // "texture 'name'" or "texture #id"
std::string describeBuffer(const ObjectTable& t, BufferHandle h);

// Looks up a handle; reports "null" / "destroyed" / "unknown" against `field` when it is not live.
const TextureDesc* liveTexture(const ObjectTable& t, TextureHandle h, const std::string& field, Report& r);
const BufferDesc* liveBuffer(const ObjectTable& t, BufferHandle h, const std::string& field, Report& r);
const SamplerDesc* liveSampler(const ObjectTable& t, SamplerHandle h, const std::string& field, Report& r);
const ShaderInfo* liveShader(const ObjectTable& t, ShaderHandle h, const std::string& field, Report& r);

// Resource descriptions against the capabilities.
void checkTextureDesc(const TextureDesc& d, const Capabilities& caps, Report& r);
void checkBufferDesc(const BufferDesc& d, Report& r);
void checkSamplerDesc(const SamplerDesc& d, Report& r);
void checkShaderDesc(const ShaderDesc& d, const Capabilities& caps, Report& r);

// Records against the reflection of their shaders.
void checkDispatch(const ObjectTable& t, const Capabilities& caps, const DispatchState& s, Report& r);
void checkDraw(const ObjectTable& t, const Capabilities& caps, const DrawCallState& s, Report& r);
// What a direct draw reads: the vertices first .. first + count - 1 of every per-vertex buffer (not for an
// indexed draw: its indices pick the vertices on the GPU) and the instances of every per-instance buffer lie
// inside their buffers, and so do an indexed draw's indices. Call after checkDraw passed.
void checkDrawFetch(const ObjectTable& t, const DrawCallState& s, const DrawArgs& a, Report& r);
void checkDrawFetch(const ObjectTable& t, const DrawCallState& s, const DrawIndexedArgs& a, Report& r);

// Transfers.
bool checkSubresource(const TextureDesc& d, TextureSubresource sub, const std::string& field, Report& r);
bool checkBufferRange(const BufferDesc& d, uint64_t offset, uint64_t size, const std::string& field, Report& r);

}  // namespace bricklight::rhi::validation
