// HeadlessContext::create: which platform API makes the context (gl_platform.h).
#include <cstdlib>
#include <string>

#include "gl_platform.h"

namespace bricklight::gl {

std::unique_ptr<HeadlessContext> HeadlessContext::create(HeadlessApi api, std::string* error) {
    std::string local;
    if (!error) error = &local;
    if (api == HeadlessApi::Auto) {
        const char* env = std::getenv("BRICKLIGHT_GL_CONTEXT");
        std::string choice = env ? env : "";
        if (choice == "osmesa") api = HeadlessApi::OSMesa;
        else if (choice == "egl") api = HeadlessApi::EGL;
        else if (choice == "wgl") api = HeadlessApi::WGL;
        else if (!choice.empty()) {
            *error = "BRICKLIGHT_GL_CONTEXT='" + choice + "' is none of 'osmesa', 'egl' and 'wgl'";
            return nullptr;
        }
    }
    if (api == HeadlessApi::OSMesa) return createOsmesaContext(error);
    if (api == HeadlessApi::EGL) return createEglContext(error);
    if (api == HeadlessApi::WGL) return createWglContext(error);
#if defined(_WIN32)
    return createWglContext(error);
#else
    std::string osmesaError, eglError;
    if (auto ctx = createOsmesaContext(&osmesaError)) return ctx;
    if (auto ctx = createEglContext(&eglError)) return ctx;
    *error = osmesaError + "; " + eglError;
    return nullptr;
#endif
}

}  // namespace bricklight::gl
