// Registry of the shaders embedded by bricklight_add_shaders(): each generated object registers its
// blob during static initialisation; findShader() looks them up by name.
#include <cstring>
#include <map>
#include <string>

#include "bricklight/shader_blob.h"

namespace bricklight::rhi {

namespace {
// Function-local so that registration from other translation units' static initialisers is safe.
std::map<std::string, const ShaderBlob*>& registry() {
    static std::map<std::string, const ShaderBlob*> shaders;
    return shaders;
}
}  // namespace

detail::ShaderRegistration::ShaderRegistration(const ShaderBlob* blobs, size_t count) {
    for (size_t i = 0; i < count; ++i) registry()[blobs[i].name] = &blobs[i];
}

const ShaderBlob* findShader(const char* name) {
    if (!name) return nullptr;
    auto it = registry().find(name);
    return it == registry().end() ? nullptr : it->second;
}

}  // namespace bricklight::rhi
