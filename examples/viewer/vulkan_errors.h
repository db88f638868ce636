// How the Vulkan viewer words a failure: one line that names the call and its VkResult.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

#include "glfw_errors.h"

namespace bricklight::viewer {

// "vulkan: <call> failed (VK_ERROR_...)".
std::string vkFailed(const char* call, VkResult r);

}  // namespace bricklight::viewer
