// Texture views (glTextureView) cached per (texture, target, format, mips, layers). A view that is the
// whole texture in its own format and target is the texture itself: no view object is made.
#pragma once

#include <map>
#include <string>
#include <tuple>

#include "gl_objects.h"

namespace bricklight::gl::detail {

class ViewCache {
public:
    // The GL texture name to bind for `v` seen as `target`; 0 with *error on failure.
    GLuint get(const Functions& gl, const TextureRecord& t, GLenum target, const ResolvedView& v, std::string* error);
    // Whether get() would return the texture itself.
    static bool isWhole(const TextureRecord& t, GLenum target, const ResolvedView& v);
    void forget(const Functions& gl, uint32_t textureId);  // the texture is being destroyed
    void clear(const Functions& gl);

private:
    using Key = std::tuple<uint32_t, GLenum, rhi::Format, uint32_t, uint32_t, uint32_t, uint32_t>;
    std::map<Key, GLuint> views_;
};

}  // namespace bricklight::gl::detail
