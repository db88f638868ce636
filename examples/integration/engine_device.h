// The "engine's" device: the application creates and owns the native API objects (its own Vulkan
// instance, device, queue and command buffers, or its own GL context), hands them to a Bricklight backend,
// and puts the validation wrapper on top. Everything else in the example, Bricklight's SDF and GI included,
// records through device() and never sees which API is underneath.
#pragma once

#include <cstdint>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace integration {

// Every message of every layer ends here; the example fails if it holds any.
class MessageLog {
public:
    void add(const char* source, bricklight::rhi::Severity severity, const std::string& message) {
        const char* kind = severity == bricklight::rhi::Severity::Error     ? "error"
                           : severity == bricklight::rhi::Severity::Warning ? "warning"
                                                                            : "info";
        if (++count_ <= 20) fprintf(stderr, "[%s %s] %s\n", source, kind, message.c_str());
    }
    uint64_t count() const { return count_; }

private:
    uint64_t count_ = 0;
};

class EngineDevice {
public:
    virtual ~EngineDevice() = default;

    // The validation wrapper over the backend: every record is checked against the shader reflection.
    bricklight::rhi::IDevice& device() { return *validation_; }
    const std::string& description() const { return description_; }
    MessageLog& messages() { return *messages_; }

    // Frame boundaries as an engine has them. Vulkan: begin the application's command buffer and make
    // the backend record into it / end it, submit it to the application's queue, then endFrame().
    virtual void beginFrame() = 0;
    virtual void endFrame() = 0;
    // After the last frame: wait for the GPU and let blocking read-backs through (Vulkan refuses them
    // while the application's command buffer is the target).
    virtual void finish() = 0;

protected:
    std::shared_ptr<MessageLog> messages_ = std::make_shared<MessageLog>();
    std::unique_ptr<bricklight::rhi::IDevice> validation_;
    std::string description_;
};

std::unique_ptr<EngineDevice> createVulkanEngineDevice(std::string* error);  // engine_device_vulkan.cpp
std::unique_ptr<EngineDevice> createGlEngineDevice(std::string* error);      // engine_device_gl.cpp

}  // namespace integration
