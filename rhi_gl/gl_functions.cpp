#include "gl_functions.h"

namespace bricklight::gl::detail {

bool Functions::load(GetProcAddress getProcAddress, std::string* error) {
    std::string missing;
    // Casting a data pointer to a function pointer is conditionally supported; every platform with GL
    // supports it (it is how every GL loader works).
#define BL_GL_LOAD(type, name)                                                          \
    name = reinterpret_cast<type>(getProcAddress("gl" #name));                          \
    if (!name) missing += std::string(missing.empty() ? "" : ", ") + "gl" #name;
    BL_GL_FUNCTIONS(BL_GL_LOAD)
#undef BL_GL_LOAD
    if (!missing.empty()) {
        *error = "the GL context lacks required functions: " + missing;
        return false;
    }
    return true;
}

}  // namespace bricklight::gl::detail
