// Draw-side GL objects and fixed-function state: framebuffer objects cached by attachment tuple, vertex
// array objects cached by vertex layout, and the per-draw raster/depth/blend state.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "gl_objects.h"

namespace bricklight::gl::detail {

struct Attachment {
    uint32_t textureId = 0;  // rhi id, so that destroying the texture drops its framebuffers
    GLuint texture = 0;      // texture or view name; 0 = none
    GLint level = 0;
    GLint layer = -1;        // -1: attach the whole level (2D texture or view); else one layer/face/slice
};

class FramebufferCache {
public:
    // 0 with *error if the combination is incomplete.
    GLuint get(const Functions& gl, const Attachment* colors, uint32_t colorCount, const Attachment& depth,
               std::string* error);
    void forget(const Functions& gl, uint32_t textureId);
    void clear(const Functions& gl);

private:
    struct Entry {
        GLuint fbo = 0;
        std::vector<uint32_t> textureIds;
    };
    std::map<std::vector<uint32_t>, Entry> fbos_;
};

class VertexArrayCache {
public:
    // The VAO for the record's vertex layout (attribute formats, bindings, divisors); buffers are bound
    // per draw with glVertexArrayVertexBuffer / glVertexArrayElementBuffer.
    GLuint get(const Functions& gl, const rhi::DrawCallState& state);
    void clear(const Functions& gl);

private:
    std::map<std::vector<uint32_t>, GLuint> vaos_;
};

GLenum compareFunc(rhi::CompareOp op);
GLenum topologyMode(rhi::PrimitiveTopology topology);

// Sets every piece of fixed-function state a draw depends on (the backend assumes nothing about what
// the app or an earlier call left): clip control, viewport, scissor, raster, depth, blend, masks.
void applyDrawState(const Functions& gl, const rhi::DrawCallState& state, uint32_t targetWidth,
                    uint32_t targetHeight, uint32_t clipDistances, bool srgbTarget);

}  // namespace bricklight::gl::detail
