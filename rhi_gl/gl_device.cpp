// Device creation, capabilities, diagnostics, markers, timing and frames; the public entry points of
// rhi_gl.h (createDevice, createHeadlessDevice, barrierCount).
#include "gl_device.h"

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <limits>

#include "gl_formats.h"
#include "gl_platform.h"

namespace bricklight::gl {
namespace detail {

namespace {
void APIENTRY debugCallback(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei, const GLchar* message,
                              const void* user) {
    static_cast<Device*>(const_cast<void*>(user))->onDebugMessage(source, type, id, severity, message);
}
}  // namespace

std::unique_ptr<Device> Device::create(const DeviceOptions& options, std::unique_ptr<HeadlessContext> owned) {
    std::unique_ptr<Device> device(new Device());
    device->ownedContext_ = std::move(owned);
    device->callback_ = options.errorCallback;
    std::string error;
    if (!device->init(options, &error)) {
        device->report(rhi::Severity::Error, "gl::createDevice: " + error);
        device->gl = Functions{};  // nothing to clean up: init creates GL objects only once it succeeds
        return nullptr;
    }
    return device;
}

bool Device::init(const DeviceOptions& options, std::string* error) {
    if (!options.getProcAddress) {
        *error = "DeviceOptions::getProcAddress is null";
        return false;
    }
    // Version first, with the three functions that exist in every context, so that a GL 3.x or
    // compatibility context gets a clear message rather than a list of missing 4.5 functions.
    auto getString = reinterpret_cast<PFNGLGETSTRINGPROC>(options.getProcAddress("glGetString"));
    auto getIntegerv = reinterpret_cast<PFNGLGETINTEGERVPROC>(options.getProcAddress("glGetIntegerv"));
    if (!getString || !getIntegerv || !getString(GL_VERSION)) {
        *error = "no GL context is current on this thread (glGetString(GL_VERSION) returned nothing)";
        return false;
    }
    GLint major = 0, minor = 0, profile = 0;
    getIntegerv(GL_MAJOR_VERSION, &major);
    getIntegerv(GL_MINOR_VERSION, &minor);
    getIntegerv(GL_CONTEXT_PROFILE_MASK, &profile);
    const char* version = reinterpret_cast<const char*>(getString(GL_VERSION));
    if (major * 10 + minor < 45 || !(profile & GL_CONTEXT_CORE_PROFILE_BIT)) {
        *error = std::string("the current context is not OpenGL 4.5 core (GL_VERSION '") + version + "', profile " +
                 ((profile & GL_CONTEXT_CORE_PROFILE_BIT) ? "core" : "compatibility") + ")";
        return false;
    }
    if (!gl.load(options.getProcAddress, error)) return false;

    drainErrors(gl);
    debugOutput_ = options.debugOutput;
    if (debugOutput_) {
        gl.Enable(GL_DEBUG_OUTPUT);
        gl.Enable(GL_DEBUG_OUTPUT_SYNCHRONOUS);  // errors reach the callback inside the failing call
        gl.DebugMessageCallback(&debugCallback, this);
        gl.DebugMessageControl(GL_DONT_CARE, GL_DONT_CARE, GL_DONT_CARE, 0, nullptr, GL_FALSE);
        gl.DebugMessageControl(GL_DONT_CARE, GL_DEBUG_TYPE_ERROR, GL_DONT_CARE, 0, nullptr, GL_TRUE);
    }
    queryCapabilities();
    GLint uboAlignment = 256;
    gl.GetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &uboAlignment);
    constants_.create(gl, uboAlignment);
    return true;
}

namespace {
uint64_t queryMaxResourceBytes(const Functions& gl, GLint extensions) {
    uint64_t gpu = 0;
    for (GLint i = 0; i < extensions; ++i) {
        const char* e = reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && !strcmp(e, "GL_NVX_gpu_memory_info")) {
            GLint kib = 0;
            gl.GetIntegerv(0x9048 /* GL_GPU_MEMORY_INFO_TOTAL_AVAILABLE_MEMORY_NVX */, &kib);
            gpu = uint64_t(kib > 0 ? kib : 0) * 1024;
        }
    }
    const uint64_t known = gpu ? gpu : hostMemoryBytes();
    const uint64_t sizeLimit = uint64_t(std::numeric_limits<GLsizeiptr>::max());
    return known ? std::min(known, sizeLimit) : sizeLimit;
}
}  // namespace

void Device::queryCapabilities() {
    caps_.backendName = "gl";
    caps_.deviceName = std::string(reinterpret_cast<const char*>(gl.GetString(GL_RENDERER))) + " (OpenGL " +
                       reinterpret_cast<const char*>(gl.GetString(GL_VERSION)) + ")";
    auto geti = [&](GLenum pname) {
        GLint v = 0;
        gl.GetIntegerv(pname, &v);
        return uint32_t(v > 0 ? v : 0);
    };
    auto getiIndexed = [&](GLenum pname, GLuint index) {
        GLint v = 0;
        gl.GetIntegeri_v(pname, index, &v);
        return uint32_t(v > 0 ? v : 0);
    };
    rhi::Limits& l = caps_.limits;
    l.maxTextureSize2D = geti(GL_MAX_TEXTURE_SIZE);
    l.maxTextureSize3D = geti(GL_MAX_3D_TEXTURE_SIZE);
    l.maxTextureArrayLayers = geti(GL_MAX_ARRAY_TEXTURE_LAYERS);
    for (GLuint i = 0; i < 3; ++i) {
        l.maxComputeGroupCount[i] = getiIndexed(GL_MAX_COMPUTE_WORK_GROUP_COUNT, i);
        l.maxComputeGroupSize[i] = getiIndexed(GL_MAX_COMPUTE_WORK_GROUP_SIZE, i);
    }
    l.maxComputeGroupInvocations = geti(GL_MAX_COMPUTE_WORK_GROUP_INVOCATIONS);
    l.maxComputeSharedMemoryBytes = geti(GL_MAX_COMPUTE_SHARED_MEMORY_SIZE);
    GLint64 ssboSize = 0;
    gl.GetInteger64v(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &ssboSize);
    l.maxStorageBufferRange = uint64_t(ssboSize > 0 ? ssboSize : 0);
    l.maxColorTargets = std::min({geti(GL_MAX_DRAW_BUFFERS), geti(GL_MAX_COLOR_ATTACHMENTS), rhi::kMaxColorTargets});
    storageAlignment_ = GLint(geti(GL_SHADER_STORAGE_BUFFER_OFFSET_ALIGNMENT));
    if (storageAlignment_ < 1) storageAlignment_ = 1;
    l.minStorageBufferOffsetAlignment = uint32_t(storageAlignment_);
    l.minUniformBufferOffsetAlignment = geti(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT);
    queryFormatSupport(gl, caps_.formatSupport);
    caps_.geometryShader = true;  // core since GL 3.2
    GLint timestampBits = 0;
    gl.GetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &timestampBits);
    caps_.timestamps = timestampBits > 0;

    GLint extensions = 0;
    gl.GetIntegerv(GL_NUM_EXTENSIONS, &extensions);
    for (GLint i = 0; i < extensions; ++i) {
        const char* e = reinterpret_cast<const char*>(gl.GetStringi(GL_EXTENSIONS, GLuint(i)));
        if (e && (!strcmp(e, "GL_ARB_texture_filter_anisotropic") || !strcmp(e, "GL_EXT_texture_filter_anisotropic")))
            anisotropy_ = true;
    }
    if (anisotropy_) gl.GetFloatv(GL_MAX_TEXTURE_MAX_ANISOTROPY, &maxAnisotropy_);
    maxResourceBytes_ = queryMaxResourceBytes(gl, extensions);
    drainErrors(gl);
}

Device::~Device() {
    if (!gl.Finish) return;  // init failed before loading: no GL objects exist
    makeCurrent();
    gl.Finish();
    timer_.destroy(gl);
    for (GLsync& f : frameFences_)
        if (f) gl.DeleteSync(f);
    for (auto& [ticket, rb] : readbacks_) {
        gl.DeleteSync(rb.fence);
        gl.DeleteBuffers(1, &rb.buffer);
    }
    views_.clear(gl);
    programs_.clear(gl);
    framebuffers_.clear(gl);
    vertexArrays_.clear(gl);
    constants_.destroy(gl);
    if (scratchIndexBuffer_) gl.DeleteBuffers(1, &scratchIndexBuffer_);
    for (auto& [id, t] : textures_)
        if (t.owned) gl.DeleteTextures(1, &t.name);
    for (auto& [id, b] : buffers_)
        if (b.owned) gl.DeleteBuffers(1, &b.name);
    for (auto& [id, s] : samplers_) gl.DeleteSamplers(1, &s.name);
    for (auto& [id, s] : shaders_) {
        gl.DeleteShader(s.shader);
        if (s.program) gl.DeleteProgram(s.program);
    }
    if (debugOutput_) gl.DebugMessageCallback(nullptr, nullptr);  // the context may outlive us
}

void Device::makeCurrent() const {
    if (ownedContext_ && !ownedContext_->isCurrent()) ownedContext_->makeCurrent();
}

void Device::report(rhi::Severity severity, const std::string& message) const {
    if (callback_) {
        callback_(severity, message);
        return;
    }
    const char* tag = severity == rhi::Severity::Error ? "error" : severity == rhi::Severity::Warning ? "warning" : "info";
    fprintf(stderr, "bricklight gl %s: %s\n", tag, message.c_str());
}

bool Device::fail(const Call& call, const std::string& message) const {
    report(rhi::Severity::Error, call.prefix() + ": " + message);
    return false;
}

void Device::onDebugMessage(GLenum, GLenum type, GLuint id, GLenum, const char* message) {
    // Only errors: performance and other notes from drivers are noise for the contract.
    if (type == GL_DEBUG_TYPE_ERROR) report(rhi::Severity::Error, std::string("GL error (id ") + std::to_string(id) + "): " + message);
}

std::string Device::missingHandle(const char* kind, uint32_t id) const {
    if (auto it = destroyed_.find(id); it != destroyed_.end()) return it->second + " (#" + std::to_string(id) + ") was destroyed";
    if (id < nextId_) return std::string(kind) + " handle #" + std::to_string(id) + " names another kind of object";
    return std::string("unknown ") + kind + " handle #" + std::to_string(id);
}

#define BL_GL_LOOKUP(Record, Handle, map, kind)                                                          \
    Record* Device::kind(rhi::Handle h, const Call& call, const std::string& field) {                    \
        if (!h) {                                                                                        \
            fail(call, field + ": null " #kind " handle");                                               \
            return nullptr;                                                                              \
        }                                                                                                \
        if (auto it = map.find(h.id); it != map.end()) return &it->second;                               \
        fail(call, field + ": " + missingHandle(#kind, h.id));                                           \
        return nullptr;                                                                                  \
    }
BL_GL_LOOKUP(TextureRecord, TextureHandle, textures_, texture)
BL_GL_LOOKUP(BufferRecord, BufferHandle, buffers_, buffer)
BL_GL_LOOKUP(SamplerRecord, SamplerHandle, samplers_, sampler)
BL_GL_LOOKUP(ShaderRecord, ShaderHandle, shaders_, shader)
#undef BL_GL_LOOKUP

// --- markers, timing, frames ------------------------------------------------------------------------

void Device::beginMarker(const char* label) {
    makeCurrent();
    std::string name = label ? label : "";
    // Bounded: GL's debug-group stack holds 64 at least, and each open marker keeps its whole path.
    if (markers_.size() + refusedMarkers_ >= rhi::kMaxMarkerDepth) {
        if (refusedMarkers_++ == 0)
            report(rhi::Severity::Error, "beginMarker '" + name.substr(0, 64) + "': more than kMaxMarkerDepth " +
                                             std::to_string(rhi::kMaxMarkerDepth) + " markers open; refused");
        return;
    }
    Marker m;
    m.path = markers_.empty() ? name : markers_.back().path + "/" + name;
    gl.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 0, -1, name.c_str());
    if (timingEnabled_ && markers_.size() < timingDepth_) {
        m.timed = true;
        m.timerIndex = timer_.begin(gl, m.path, frame_);
    }
    markers_.push_back(std::move(m));
}

void Device::endMarker() {
    makeCurrent();
    if (refusedMarkers_) {
        --refusedMarkers_;
        return;
    }
    if (markers_.empty()) {
        report(rhi::Severity::Error, "endMarker: no marker is open");
        return;
    }
    if (markers_.back().timed) timer_.end(gl, markers_.back().timerIndex);
    gl.PopDebugGroup();
    markers_.pop_back();
}

std::vector<rhi::MarkerTiming> Device::takeTimings() {
    makeCurrent();
    return timer_.take(gl);
}

void Device::endFrame() {
    makeCurrent();
    GLsync& slot = frameFences_[frame_ % kFramesInFlight];
    if (slot) {  // the frame kFramesInFlight back: the only wait in a normal frame
        gl.ClientWaitSync(slot, GL_SYNC_FLUSH_COMMANDS_BIT, GLuint64(-1));
        gl.DeleteSync(slot);
    }
    slot = gl.FenceSync(GL_SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.Flush();
    ++frame_;
}

void Device::waitIdle() {
    makeCurrent();
    gl.Finish();
}

void Device::pushLabel(const char* label) {
    if (label && *label) gl.PushDebugGroup(GL_DEBUG_SOURCE_APPLICATION, 1, -1, label);
}
void Device::popLabel(const char* label) {
    if (label && *label) gl.PopDebugGroup();
}

}  // namespace detail

std::unique_ptr<rhi::IDevice> createDevice(const DeviceOptions& options) {
    return detail::Device::create(options, nullptr);
}

std::unique_ptr<rhi::IDevice> createHeadlessDevice(HeadlessApi api, rhi::ErrorCallback callback, std::string* error) {
    std::string local;
    if (!error) error = &local;
    auto context = HeadlessContext::create(api, error);
    if (!context) return nullptr;
    DeviceOptions options;
    options.getProcAddress = context->getProcAddress();
    // Creation errors go both to the callback and to *error.
    options.errorCallback = [callback, error](rhi::Severity s, const std::string& m) {
        if (s == rhi::Severity::Error && error->empty()) *error = m;
        if (callback) callback(s, m);
        else fprintf(stderr, "bricklight gl: %s\n", m.c_str());
    };
    auto device = detail::Device::create(options, std::move(context));
    if (device) device->setErrorCallback(std::move(callback));
    return device;
}

std::optional<uint64_t> barrierCount(rhi::IDevice& device) {
    auto* gl = dynamic_cast<detail::Device*>(&device);
    return gl ? std::optional(gl->barrierCount()) : std::nullopt;
}

}  // namespace bricklight::gl
