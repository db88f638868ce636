// Devices for tests on both backends: Vulkan with the validation layer and synchronization validation on,
// GL headless; every message a device reports goes into `messages` (tests require it to stay empty).
//
// The device a test gets is the backend under our validation wrapper (rhi::createValidationDevice), so
// every record the SDF, GI and renderer make is checked against its shader's reflection on every run;
// a message of any severity from the wrapper fails the test. BRICKLIGHT_TEST_VALIDATION_WRAPPER=0 hands
// out the bare backend instead (to tell the wrapper's cost or a wrapper bug from a backend one).
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::testing {

struct TestDevice {
    std::string backend;
    std::unique_ptr<rhi::IDevice> backendDevice;  // the backend itself (declared first: destroyed last)
    std::unique_ptr<rhi::IDevice> wrapper;        // the validation wrapper around it, when on
    rhi::IDevice* device = nullptr;               // what tests call: the wrapper, or the backend
    std::shared_ptr<std::vector<std::string>> messages = std::make_shared<std::vector<std::string>>();
};
// "vulkan" or "gl".
TestDevice makeDevice(const std::string& backend);

}  // namespace bricklight::testing
