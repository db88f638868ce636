// Headless GL 4.5 core contexts through OSMesa or EGL (Linux and other Unix systems), both loaded with dlopen
// so that nothing links libGL/libOSMesa/libEGL. The GL function pointers come from the same library's
// GetProcAddress. The host's memory size is here too (the platform's part of gl_device.cpp's limits).
#include <dlfcn.h>
#include <unistd.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "gl_platform.h"

namespace bricklight::gl {

namespace {

// --- OSMesa ---------------------------------------------------------------------------------------
// Constants of GL/osmesa.h, written out because that header pulls in GL/gl.h (clashes with glcorearb).
constexpr int kOsmesaFormat = 0x22, kOsmesaRgba = 0x1908 /* GL_RGBA */, kOsmesaDepthBits = 0x30,
              kOsmesaStencilBits = 0x31, kOsmesaAccumBits = 0x32, kOsmesaProfile = 0x33,
              kOsmesaCoreProfile = 0x34, kOsmesaMajor = 0x36, kOsmesaMinor = 0x37;
constexpr unsigned kGlUnsignedByte = 0x1401;

struct OsmesaApi {
    void* lib = nullptr;
    void* (*createContextAttribs)(const int*, void*) = nullptr;
    unsigned char (*makeCurrent)(void*, void*, unsigned, int, int) = nullptr;
    void (*destroyContext)(void*) = nullptr;
    void* (*getCurrentContext)() = nullptr;
    void* (*getProcAddress)(const char*) = nullptr;  // really returns OSMESAproc
};
OsmesaApi g_osmesa;  // the library stays loaded for the process: Mesa does not like being unloaded

void* osmesaGetProc(const char* name) { return g_osmesa.getProcAddress ? g_osmesa.getProcAddress(name) : nullptr; }

bool loadOsmesa(std::string* error) {
    if (g_osmesa.lib) return true;
    void* lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib) lib = dlopen("libOSMesa.so", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        *error = std::string("OSMesa: cannot load libOSMesa.so.8 (") + dlerror() + ")";
        return false;
    }
    OsmesaApi api;
    api.lib = lib;
    api.createContextAttribs = reinterpret_cast<decltype(api.createContextAttribs)>(dlsym(lib, "OSMesaCreateContextAttribs"));
    api.makeCurrent = reinterpret_cast<decltype(api.makeCurrent)>(dlsym(lib, "OSMesaMakeCurrent"));
    api.destroyContext = reinterpret_cast<decltype(api.destroyContext)>(dlsym(lib, "OSMesaDestroyContext"));
    api.getCurrentContext = reinterpret_cast<decltype(api.getCurrentContext)>(dlsym(lib, "OSMesaGetCurrentContext"));
    api.getProcAddress = reinterpret_cast<decltype(api.getProcAddress)>(dlsym(lib, "OSMesaGetProcAddress"));
    if (!api.createContextAttribs || !api.makeCurrent || !api.destroyContext || !api.getCurrentContext ||
        !api.getProcAddress) {
        *error = "OSMesa: libOSMesa lacks OSMesaCreateContextAttribs (needs Mesa >= 12)";
        return false;
    }
    g_osmesa = api;
    return true;
}

class OsmesaContext final : public HeadlessContext {
public:
    static std::unique_ptr<HeadlessContext> create(std::string* error) {
        if (!loadOsmesa(error)) return nullptr;
        const int attribs[] = {kOsmesaFormat, kOsmesaRgba, kOsmesaDepthBits, 0, kOsmesaStencilBits, 0,
                               kOsmesaAccumBits, 0, kOsmesaProfile, kOsmesaCoreProfile, kOsmesaMajor, 4,
                               kOsmesaMinor, 5, 0};
        void* ctx = g_osmesa.createContextAttribs(attribs, nullptr);
        if (!ctx) {
            *error = "OSMesa: OSMesaCreateContextAttribs failed for a GL 4.5 core context";
            return nullptr;
        }
        auto result = std::unique_ptr<OsmesaContext>(new OsmesaContext(ctx));
        result->makeCurrent();
        if (!result->isCurrent()) {
            *error = "OSMesa: OSMesaMakeCurrent failed";
            return nullptr;
        }
        return result;
    }
    ~OsmesaContext() override {
        if (ctx_) g_osmesa.destroyContext(ctx_);
    }
    void makeCurrent() override { g_osmesa.makeCurrent(ctx_, buffer_, kGlUnsignedByte, kSize, kSize); }
    bool isCurrent() const override { return g_osmesa.getCurrentContext() == ctx_; }
    GetProcAddress getProcAddress() const override { return &osmesaGetProc; }
    const char* apiName() const override { return "osmesa"; }

private:
    static constexpr int kSize = 4;  // the default framebuffer is never used: everything draws to FBOs
    explicit OsmesaContext(void* ctx) : ctx_(ctx) {}
    void* ctx_ = nullptr;
    unsigned char buffer_[kSize * kSize * 4] = {};
};

// --- EGL --------------------------------------------------------------------------------------------
// EGL tokens (EGL/egl.h, EGL/eglext.h), written out to avoid the platform headers' X11 includes.
using EGLDisplay = void*;
using EGLContext = void*;
using EGLConfig = void*;
using EGLDeviceEXT = void*;
using EGLint = int32_t;
constexpr EGLint kEglNone = 0x3038, kEglExtensions = 0x3055, kEglOpenglApi = 0x30A2,
                 kEglRenderableType = 0x3040, kEglOpenglBit = 0x0008, kEglSurfaceType = 0x3033,
                 kEglContextMajor = 0x3098, kEglContextMinor = 0x30FB, kEglProfileMask = 0x30FD,
                 kEglCoreProfileBit = 0x1, kEglPlatformDevice = 0x313F, kEglPlatformSurfacelessMesa = 0x31DD;

struct EglApi {
    void* lib = nullptr;
    void* (*getProcAddress)(const char*) = nullptr;
    EGLDisplay (*getDisplay)(void*) = nullptr;
    unsigned (*initialize)(EGLDisplay, EGLint*, EGLint*) = nullptr;
    const char* (*queryString)(EGLDisplay, EGLint) = nullptr;
    unsigned (*bindApi)(unsigned) = nullptr;
    unsigned (*chooseConfig)(EGLDisplay, const EGLint*, EGLConfig*, EGLint, EGLint*) = nullptr;
    EGLContext (*createContext)(EGLDisplay, EGLConfig, EGLContext, const EGLint*) = nullptr;
    unsigned (*makeCurrent)(EGLDisplay, void*, void*, EGLContext) = nullptr;
    unsigned (*destroyContext)(EGLDisplay, EGLContext) = nullptr;
    EGLContext (*getCurrentContext)() = nullptr;
    EGLint (*getError)() = nullptr;
    // Extensions, through eglGetProcAddress.
    unsigned (*queryDevices)(EGLint, EGLDeviceEXT*, EGLint*) = nullptr;
    EGLDisplay (*getPlatformDisplay)(unsigned, void*, const EGLint*) = nullptr;
};
EglApi g_egl;

void* eglGetProc(const char* name) { return g_egl.getProcAddress ? g_egl.getProcAddress(name) : nullptr; }

bool hasExtension(const char* list, const char* name) {
    if (!list) return false;
    size_t n = strlen(name);
    for (const char* p = strstr(list, name); p; p = strstr(p + n, name))
        if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
    return false;
}

bool loadEgl(std::string* error) {
    if (g_egl.lib) return true;
    void* lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        *error = std::string("EGL: cannot load libEGL.so.1 (") + dlerror() + ")";
        return false;
    }
    EglApi api;
    api.lib = lib;
#define BL_EGL_SYM(field, sym) api.field = reinterpret_cast<decltype(api.field)>(dlsym(lib, sym))
    BL_EGL_SYM(getProcAddress, "eglGetProcAddress");
    BL_EGL_SYM(getDisplay, "eglGetDisplay");
    BL_EGL_SYM(initialize, "eglInitialize");
    BL_EGL_SYM(queryString, "eglQueryString");
    BL_EGL_SYM(bindApi, "eglBindAPI");
    BL_EGL_SYM(chooseConfig, "eglChooseConfig");
    BL_EGL_SYM(createContext, "eglCreateContext");
    BL_EGL_SYM(makeCurrent, "eglMakeCurrent");
    BL_EGL_SYM(destroyContext, "eglDestroyContext");
    BL_EGL_SYM(getCurrentContext, "eglGetCurrentContext");
    BL_EGL_SYM(getError, "eglGetError");
#undef BL_EGL_SYM
    if (!api.getProcAddress || !api.getDisplay || !api.initialize || !api.queryString || !api.bindApi ||
        !api.chooseConfig || !api.createContext || !api.makeCurrent || !api.destroyContext ||
        !api.getCurrentContext || !api.getError) {
        *error = "EGL: libEGL.so.1 lacks core EGL 1.4 entry points";
        return false;
    }
    api.queryDevices = reinterpret_cast<decltype(api.queryDevices)>(api.getProcAddress("eglQueryDevicesEXT"));
    api.getPlatformDisplay =
        reinterpret_cast<decltype(api.getPlatformDisplay)>(api.getProcAddress("eglGetPlatformDisplayEXT"));
    g_egl = api;
    return true;
}

class EglContext final : public HeadlessContext {
public:
    static std::unique_ptr<HeadlessContext> create(std::string* error) {
        if (!loadEgl(error)) return nullptr;
        const char* client = g_egl.queryString(nullptr, kEglExtensions);
        std::vector<EGLDisplay> candidates;
        // A GPU machine with no display server: enumerate devices (EGL_EXT_platform_device).
        if (g_egl.queryDevices && g_egl.getPlatformDisplay && hasExtension(client, "EGL_EXT_platform_device")) {
            EGLDeviceEXT devices[16];
            EGLint count = 0;
            if (g_egl.queryDevices(16, devices, &count))
                for (EGLint i = 0; i < count; ++i)
                    if (EGLDisplay d = g_egl.getPlatformDisplay(kEglPlatformDevice, devices[i], nullptr))
                        candidates.push_back(d);
        }
        if (g_egl.getPlatformDisplay && hasExtension(client, "EGL_MESA_platform_surfaceless"))
            if (EGLDisplay d = g_egl.getPlatformDisplay(kEglPlatformSurfacelessMesa, nullptr, nullptr))
                candidates.push_back(d);
        if (EGLDisplay d = g_egl.getDisplay(nullptr)) candidates.push_back(d);

        std::string reasons;
        for (EGLDisplay display : candidates) {
            std::string why;
            if (auto ctx = tryDisplay(display, &why)) return ctx;
            reasons += (reasons.empty() ? "" : "; ") + why;
        }
        *error = "EGL: no display gave a surfaceless GL 4.5 core context" +
                 (reasons.empty() ? std::string(" (no display)") : " (" + reasons + ")");
        return nullptr;
    }
    ~EglContext() override {
        // eglTerminate is not called: EGL displays are shared by the whole process, and terminating one
        // would destroy every other context made on it.
        if (isCurrent()) g_egl.makeCurrent(display_, nullptr, nullptr, nullptr);
        g_egl.destroyContext(display_, ctx_);
    }
    void makeCurrent() override { g_egl.makeCurrent(display_, nullptr, nullptr, ctx_); }
    bool isCurrent() const override { return g_egl.getCurrentContext() == ctx_; }
    GetProcAddress getProcAddress() const override { return &eglGetProc; }
    const char* apiName() const override { return "egl"; }

private:
    EglContext(EGLDisplay display, EGLContext ctx) : display_(display), ctx_(ctx) {}

    static std::unique_ptr<HeadlessContext> tryDisplay(EGLDisplay display, std::string* why) {
        EGLint major = 0, minor = 0;
        if (!g_egl.initialize(display, &major, &minor)) {
            *why = "eglInitialize failed";
            return nullptr;
        }
        if (!hasExtension(g_egl.queryString(display, kEglExtensions), "EGL_KHR_surfaceless_context")) {
            *why = "no EGL_KHR_surfaceless_context";
            return nullptr;
        }
        if (!g_egl.bindApi(kEglOpenglApi)) {
            *why = "eglBindAPI(EGL_OPENGL_API) failed";
            return nullptr;
        }
        const EGLint configAttribs[] = {kEglRenderableType, kEglOpenglBit, kEglSurfaceType, 0, kEglNone};
        EGLConfig config = nullptr;
        EGLint numConfigs = 0;
        if (!g_egl.chooseConfig(display, configAttribs, &config, 1, &numConfigs) || numConfigs < 1) {
            *why = "no EGL config with EGL_OPENGL_BIT";
            return nullptr;
        }
        const EGLint contextAttribs[] = {kEglContextMajor, 4, kEglContextMinor, 5, kEglProfileMask,
                                         kEglCoreProfileBit, kEglNone};
        EGLContext ctx = g_egl.createContext(display, config, nullptr, contextAttribs);
        if (!ctx) {
            *why = "eglCreateContext(GL 4.5 core) failed with error 0x" + std::to_string(g_egl.getError());
            return nullptr;
        }
        if (!g_egl.makeCurrent(display, nullptr, nullptr, ctx)) {
            g_egl.destroyContext(display, ctx);
            *why = "eglMakeCurrent with no surface failed";
            return nullptr;
        }
        return std::unique_ptr<HeadlessContext>(new EglContext(display, ctx));
    }

    EGLDisplay display_;
    EGLContext ctx_;
};

}  // namespace

std::unique_ptr<HeadlessContext> createOsmesaContext(std::string* error) { return OsmesaContext::create(error); }
std::unique_ptr<HeadlessContext> createEglContext(std::string* error) { return EglContext::create(error); }
std::unique_ptr<HeadlessContext> createWglContext(std::string* error) {
    *error = "WGL: there is no WGL on this platform (it is Windows' GL context API)";
    return nullptr;
}

uint64_t hostMemoryBytes() {
    const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
    return pages > 0 && pageSize > 0 ? uint64_t(pages) * uint64_t(pageSize) : 0;
}

}  // namespace bricklight::gl
