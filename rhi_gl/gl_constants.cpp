#include "gl_constants.h"

#include <cstring>

namespace bricklight::gl::detail {

void ConstantRing::create(const Functions& gl, GLint alignment) {
    alignment_ = alignment > 0 ? alignment : 256;
    gl.CreateBuffers(1, &buffer_);
    gl.NamedBufferStorage(buffer_, kSize, nullptr, GL_DYNAMIC_STORAGE_BIT);
    gl.ObjectLabel(GL_BUFFER, buffer_, -1, "bricklight constants ring");
}

void ConstantRing::destroy(const Functions& gl) {
    if (buffer_) gl.DeleteBuffers(1, &buffer_);
    buffer_ = 0;
}

GLintptr ConstantRing::push(const Functions& gl, const void* data, uint32_t size, uint32_t bindSize) {
    unsigned char bytes[256] = {};
    if (size) memcpy(bytes, data, size);
    GLintptr offset = (head_ + alignment_ - 1) / alignment_ * alignment_;
    if (offset + GLintptr(bindSize) > kSize) offset = 0;
    gl.NamedBufferSubData(buffer_, offset, bindSize, bytes);
    head_ = offset + bindSize;
    return offset;
}

}  // namespace bricklight::gl::detail
