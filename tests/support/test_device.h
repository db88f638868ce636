// Devices for tests on both backends: Vulkan with the validation layer and synchronization validation on,
// GL headless; every message a device reports goes into `messages` (tests require it to stay empty).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::testing {

struct TestDevice {
    std::string backend;
    std::unique_ptr<rhi::IDevice> device;
    std::shared_ptr<std::vector<std::string>> messages = std::make_shared<std::vector<std::string>>();
};
// "vulkan" or "gl".
TestDevice makeDevice(const std::string& backend);

}  // namespace bricklight::testing
