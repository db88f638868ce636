// OpenGL as an engine has it: a GL 4.5 core context made current by the application, and the backend
// created on it with the context's getProcAddress. An engine passes its window's context and loader
// (e.g. glfwGetProcAddress); this example has no window, so its context is a headless one.
#include "bricklight/rhi_gl.h"
#include "bricklight/rhi_validation.h"
#include "engine_device.h"

namespace integration {

namespace {

using bricklight::rhi::Severity;

class GlEngineDevice final : public EngineDevice {
public:
    ~GlEngineDevice() override {
        // The device's GL objects are deleted on the context, so the context goes last.
        validation_.reset();
        backend_.reset();
        context_.reset();
    }

    bool create(std::string* error) {
        context_ = bricklight::gl::HeadlessContext::create(bricklight::gl::HeadlessApi::Auto, error);
        if (!context_) return false;
        context_->makeCurrent();  // the backend uses whatever context is current on the calling thread
        bricklight::gl::DeviceOptions options;
        options.getProcAddress = context_->getProcAddress();
        options.debugOutput = true;  // GL errors (KHR_debug) become messages
        std::shared_ptr<MessageLog> log = messages_;
        options.errorCallback = [log](Severity s, const std::string& m) { log->add("gl backend", s, m); };
        backend_ = bricklight::gl::createDevice(options);
        if (!backend_) {
            *error = "gl::createDevice failed (see the messages above)";
            return false;
        }
        validation_ = bricklight::rhi::createValidationDevice(*backend_);
        validation_->setErrorCallback([log](Severity s, const std::string& m) { log->add("rhi", s, m); });
        description_ = std::string("gl (application's own context, ") + context_->apiName() + ") on " +
                       backend_->capabilities().deviceName;
        return true;
    }

    // GL has no command buffers to hand over: the backend issues GL calls directly on the current context.
    void beginFrame() override {}
    void endFrame() override { device().endFrame(); }  // fences the frame; waits only for the frame two back
    void finish() override { device().waitIdle(); }

private:
    std::unique_ptr<bricklight::gl::HeadlessContext> context_;
    std::unique_ptr<bricklight::rhi::IDevice> backend_;
};

}  // namespace

std::unique_ptr<EngineDevice> createGlEngineDevice(std::string* error) {
    auto d = std::make_unique<GlEngineDevice>();
    if (!d->create(error)) return nullptr;
    return d;
}

}  // namespace integration
