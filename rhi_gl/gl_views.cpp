#include "gl_views.h"

#include "gl_formats.h"

namespace bricklight::gl::detail {

bool ViewCache::isWhole(const TextureRecord& t, GLenum target, const ResolvedView& v) {
    return target == t.target && v.format == t.desc.format && v.baseMip == 0 && v.mipCount == t.desc.mipLevels &&
           v.baseLayer == 0 && v.layerCount == rhi::textureLayerCount(t.desc);
}

GLuint ViewCache::get(const Functions& gl, const TextureRecord& t, GLenum target, const ResolvedView& v,
                      std::string* error) {
    if (isWhole(t, target, v)) return t.name;
    Key key{t.id, target, v.format, v.baseMip, v.mipCount, v.baseLayer, v.layerCount};
    if (auto it = views_.find(key); it != views_.end()) return it->second;
    if (!t.immutable) {
        *error = describe(t) + " is a wrapped texture without immutable storage: it can only be bound whole, "
                 "in its own format (glTextureView needs glTexStorage)";
        return 0;
    }
    // glTextureView needs a name from glGenTextures that was never bound: glCreateTextures would already
    // have made the object. This is the one place the backend is not DSA.
    GLuint view = 0;
    gl.GenTextures(1, &view);
    drainErrors(gl);
    gl.TextureView(view, target, t.name, glFormat(v.format).internalFormat, v.baseMip, v.mipCount, v.baseLayer,
                   target == GL_TEXTURE_3D ? 1 : v.layerCount);
    if (GLenum err = gl.GetError(); err != GL_NO_ERROR) {
        gl.DeleteTextures(1, &view);
        *error = "glTextureView of " + describe(t) + " failed (GL error " + hex(err) + ")";
        return 0;
    }
    std::string label = t.desc.debugName + " (view)";
    gl.ObjectLabel(GL_TEXTURE, view, -1, label.c_str());
    views_.emplace(key, view);
    return view;
}

void ViewCache::forget(const Functions& gl, uint32_t textureId) {
    for (auto it = views_.lower_bound(Key{textureId, 0, rhi::Format::Unknown, 0, 0, 0, 0});
         it != views_.end() && std::get<0>(it->first) == textureId;) {
        gl.DeleteTextures(1, &it->second);
        it = views_.erase(it);
    }
}

void ViewCache::clear(const Functions& gl) {
    for (auto& [key, name] : views_) gl.DeleteTextures(1, &name);
    views_.clear();
}

}  // namespace bricklight::gl::detail
