// What the GL device keeps per rhi object. Handles are ids from one counter shared by every object kind,
// never reused, so a destroyed handle is always told from a live one.
#pragma once

#include <string>

#include "bricklight/rhi.h"
#include "gl_functions.h"

namespace bricklight::gl::detail {

struct TextureRecord {
    uint32_t id = 0;
    rhi::TextureDesc desc;
    GLuint name = 0;
    GLenum target = 0;
    bool owned = true;      // false for wrapNativeTexture: forgotten, not deleted
    bool immutable = true;  // glTextureView needs immutable storage (wrapped textures may lack it)
    uint64_t lastShaderWrite = 0;  // BarrierTracker serial of the last SSBO/image write (0 = none)
};

struct BufferRecord {
    uint32_t id = 0;
    rhi::BufferDesc desc;
    GLuint name = 0;
    bool owned = true;
    uint64_t lastShaderWrite = 0;
};

struct SamplerRecord {
    uint32_t id = 0;
    rhi::SamplerDesc desc;
    GLuint name = 0;
};

struct ShaderRecord {
    uint32_t id = 0;
    const rhi::ShaderBlob* blob = nullptr;
    std::string name;
    GLuint shader = 0;
    GLuint program = 0;          // compute shaders: linked at createShader
    uint32_t clipDistances = 0;  // vertex/geometry: gl_ClipDistance[] entries written (GL must enable them)
};

// A TextureView with its defaults filled in and checked against the texture.
struct ResolvedView {
    rhi::Format format = rhi::Format::Unknown;
    uint32_t baseMip = 0, mipCount = 0, baseLayer = 0, layerCount = 0;
};

inline std::string hex(unsigned value) {
    static const char* digits = "0123456789ABCDEF";
    std::string s;
    do {
        s.insert(s.begin(), digits[value & 15]);
        value >>= 4;
    } while (value);
    return "0x" + s;
}
// Drains glGetError so that the next check sees only what the next call does (bounded: a lost context
// may keep answering).
inline void drainErrors(const Functions& gl) {
    for (int i = 0; i < 16 && gl.GetError() != GL_NO_ERROR; ++i) {
    }
}

inline std::string quotedName(const char* kind, uint32_t id, const std::string& debugName) {
    return std::string(kind) + (debugName.empty() ? " #" + std::to_string(id) : " '" + debugName + "'");
}
inline std::string describe(const TextureRecord& t) { return quotedName("texture", t.id, t.desc.debugName); }
inline std::string describe(const BufferRecord& b) { return quotedName("buffer", b.id, b.desc.debugName); }
inline std::string describe(const SamplerRecord& s) { return quotedName("sampler", s.id, s.desc.debugName); }
inline std::string describe(const ShaderRecord& s) { return "shader '" + s.name + "'"; }

}  // namespace bricklight::gl::detail
