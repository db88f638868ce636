// Headless GL 4.5 core contexts on Windows through WGL. opengl32.dll is loaded at run time (nothing links it,
// as on Unix nothing links libGL); the context lives on a hidden 1x1 window of its own, whose default
// framebuffer nothing uses (all rendering goes to framebuffer objects). A legacy context is made first
// because wglCreateContextAttribsARB, which makes the core one, is only reachable through a current context.
// The window and the context belong to the thread that creates them: Windows destroys them only from there.
// The host's memory size is here too (the platform's part of gl_device.cpp's limits).
#define WIN32_LEAN_AND_MEAN
#ifndef NOMINMAX
#define NOMINMAX
#endif
#include <windows.h>

#include <string>

#include "gl_platform.h"

namespace bricklight::gl {

namespace {

// WGL_ARB_create_context and WGL_ARB_create_context_profile tokens (wglext.h).
constexpr int kWglContextMajor = 0x2091, kWglContextMinor = 0x2092, kWglContextProfileMask = 0x9126,
              kWglContextCoreProfileBit = 0x1;

struct WglApi {
    HMODULE lib = nullptr;
    PROC(WINAPI* getProcAddress)(LPCSTR) = nullptr;
    HGLRC(WINAPI* createContext)(HDC) = nullptr;
    BOOL(WINAPI* deleteContext)(HGLRC) = nullptr;
    BOOL(WINAPI* makeCurrent)(HDC, HGLRC) = nullptr;
    HGLRC(WINAPI* getCurrentContext)() = nullptr;
    HGLRC(WINAPI* createContextAttribs)(HDC, HGLRC, const int*) = nullptr;  // through a current context
};
WglApi g_wgl;  // opengl32.dll stays loaded for the process, as OSMesa and EGL do on Unix
const char* const kWindowClass = "BricklightHeadlessGL";

std::string errorText(DWORD code) { return "error " + std::to_string(code); }
std::string lastErrorText() { return errorText(GetLastError()); }

template <typename T>
bool symbol(HMODULE lib, const char* name, T* out) {
    *out = reinterpret_cast<T>(reinterpret_cast<void*>(::GetProcAddress(lib, name)));
    return *out != nullptr;
}

bool loadWgl(std::string* error) {
    if (g_wgl.lib) return true;
    HMODULE lib = LoadLibraryA("opengl32.dll");
    if (!lib) {
        *error = "WGL: cannot load opengl32.dll (" + lastErrorText() + ")";
        return false;
    }
    WglApi api;
    api.lib = lib;
    if (!symbol(lib, "wglGetProcAddress", &api.getProcAddress) || !symbol(lib, "wglCreateContext", &api.createContext) ||
        !symbol(lib, "wglDeleteContext", &api.deleteContext) || !symbol(lib, "wglMakeCurrent", &api.makeCurrent) ||
        !symbol(lib, "wglGetCurrentContext", &api.getCurrentContext)) {
        FreeLibrary(lib);
        *error = "WGL: opengl32.dll lacks the WGL 1.0 entry points";
        return false;
    }
    WNDCLASSA windowClass{};
    windowClass.style = CS_OWNDC;
    windowClass.lpfnWndProc = DefWindowProcA;
    windowClass.hInstance = GetModuleHandleA(nullptr);
    windowClass.lpszClassName = kWindowClass;
    if (!RegisterClassA(&windowClass)) {
        const DWORD code = GetLastError();
        if (code != ERROR_CLASS_ALREADY_EXISTS) {
            FreeLibrary(lib);
            *error = "WGL: RegisterClass failed (" + errorText(code) + ")";
            return false;
        }
    }
    g_wgl = api;
    return true;
}

// (::GetProcAddress is the Win32 function; GetProcAddress alone names rhi_gl.h's type here.)
// GL 1.1 functions are exported by opengl32.dll and not returned by wglGetProcAddress; some drivers return
// small integers instead of null for names they do not know.
void* wglGetProc(const char* name) {
    PROC p = g_wgl.getProcAddress ? g_wgl.getProcAddress(name) : nullptr;
    const auto value = reinterpret_cast<intptr_t>(p);
    if (value == 0 || value == 1 || value == 2 || value == 3 || value == -1)
        p = g_wgl.lib ? ::GetProcAddress(g_wgl.lib, name) : nullptr;
    return reinterpret_cast<void*>(p);
}

class WglContext final : public HeadlessContext {
public:
    static std::unique_ptr<HeadlessContext> create(std::string* error) {
        if (!loadWgl(error)) return nullptr;
        HWND window = CreateWindowExA(0, kWindowClass, "Bricklight headless GL", WS_POPUP, 0, 0, 1, 1, nullptr,
                                      nullptr, GetModuleHandleA(nullptr), nullptr);
        if (!window) {
            *error = "WGL: CreateWindowEx failed for the hidden window (" + lastErrorText() + ")";
            return nullptr;
        }
        // Owns the window (and, once made, the context) from here on: every failure below cleans up.
        auto result = std::unique_ptr<WglContext>(new WglContext(window, GetDC(window)));
        PIXELFORMATDESCRIPTOR pfd{};
        pfd.nSize = sizeof(pfd);
        pfd.nVersion = 1;
        pfd.dwFlags = PFD_DRAW_TO_WINDOW | PFD_SUPPORT_OPENGL | PFD_DOUBLEBUFFER;
        pfd.iPixelType = PFD_TYPE_RGBA;
        pfd.cColorBits = 32;
        pfd.iLayerType = PFD_MAIN_PLANE;
        const int format = ChoosePixelFormat(result->dc_, &pfd);
        if (!format || !SetPixelFormat(result->dc_, format, &pfd)) {
            *error = "WGL: no RGBA pixel format for the hidden window (" + lastErrorText() + ")";
            return nullptr;
        }
        HGLRC legacy = g_wgl.createContext(result->dc_);
        if (!legacy || !g_wgl.makeCurrent(result->dc_, legacy)) {
            const DWORD code = GetLastError();  // before the clean-up overwrites it
            if (legacy) g_wgl.deleteContext(legacy);
            *error = std::string(legacy ? "WGL: wglMakeCurrent failed for the legacy context (" : "WGL: wglCreateContext failed (") +
                     errorText(code) + ")";
            return nullptr;
        }
        decltype(g_wgl.createContextAttribs) createAttribs = nullptr;
        createAttribs = reinterpret_cast<decltype(createAttribs)>(wglGetProc("wglCreateContextAttribsARB"));
        const int attribs[] = {kWglContextMajor, 4, kWglContextMinor, 5, kWglContextProfileMask,
                               kWglContextCoreProfileBit, 0};
        HGLRC core = createAttribs ? createAttribs(result->dc_, nullptr, attribs) : nullptr;
        const DWORD coreError = GetLastError();  // ERROR_INVALID_VERSION_ARB and the like, before the clean-up
        g_wgl.makeCurrent(nullptr, nullptr);
        g_wgl.deleteContext(legacy);
        if (!createAttribs) {
            *error = "WGL: the driver lacks WGL_ARB_create_context (needed for a GL 4.5 core context)";
            return nullptr;
        }
        if (!core) {
            *error = "WGL: wglCreateContextAttribsARB(GL 4.5 core) failed (" + errorText(coreError) + ")";
            return nullptr;
        }
        result->context_ = core;
        result->makeCurrent();
        if (!result->isCurrent()) {
            *error = "WGL: wglMakeCurrent failed for the GL 4.5 core context (" + lastErrorText() + ")";
            return nullptr;
        }
        return result;
    }
    ~WglContext() override {
        if (context_) {
            if (isCurrent()) g_wgl.makeCurrent(nullptr, nullptr);
            g_wgl.deleteContext(context_);
        }
        if (dc_) ReleaseDC(window_, dc_);
        DestroyWindow(window_);
    }
    void makeCurrent() override { g_wgl.makeCurrent(dc_, context_); }
    bool isCurrent() const override { return context_ && g_wgl.getCurrentContext() == context_; }
    GetProcAddress getProcAddress() const override { return &wglGetProc; }
    const char* apiName() const override { return "wgl"; }

private:
    WglContext(HWND window, HDC dc) : window_(window), dc_(dc) {}
    HWND window_;
    HDC dc_;
    HGLRC context_ = nullptr;
};

}  // namespace

std::unique_ptr<HeadlessContext> createWglContext(std::string* error) { return WglContext::create(error); }
std::unique_ptr<HeadlessContext> createOsmesaContext(std::string* error) {
    *error = "OSMesa: not available on Windows (the headless context there is WGL's)";
    return nullptr;
}
std::unique_ptr<HeadlessContext> createEglContext(std::string* error) {
    *error = "EGL: not available on Windows (the headless context there is WGL's)";
    return nullptr;
}

uint64_t hostMemoryBytes() {
    MEMORYSTATUSEX status{};
    status.dwLength = sizeof(status);
    return GlobalMemoryStatusEx(&status) ? uint64_t(status.ullTotalPhys) : 0;
}

}  // namespace bricklight::gl
