// Inline constants: the record's bytes are copied at call time into a ring uniform buffer
// (glNamedBufferSubData at offsets aligned to GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT) and bound with
// glBindBufferRange. GL orders BufferSubData after the draws/dispatches already issued that read the
// ring, so wrapping around is correct; the ring only keeps drivers from stalling on every call.
#pragma once

#include "gl_functions.h"

namespace bricklight::gl::detail {

class ConstantRing {
public:
    void create(const Functions& gl, GLint alignment);
    void destroy(const Functions& gl);
    // Copies `size` bytes, zero-padded to `bindSize` (>= size, <= 256), and returns the ring offset.
    GLintptr push(const Functions& gl, const void* data, uint32_t size, uint32_t bindSize);
    GLuint buffer() const { return buffer_; }

private:
    static constexpr GLsizeiptr kSize = 256 * 1024;
    GLuint buffer_ = 0;
    GLintptr head_ = 0;
    GLint alignment_ = 256;
};

}  // namespace bricklight::gl::detail
