// How the Vulkan viewer words a failure: one line that names the call and its VkResult, with GLFW's own
// reason where a GLFW call failed (GLFW gives that reason only to its error callback, so we keep it).
#pragma once

#include <vulkan/vulkan.h>

#include <string>

namespace bricklight::viewer {

// "vulkan: <call> failed (VK_ERROR_...)".
std::string vkFailed(const char* call, VkResult r);

// Routes GLFW's error messages to lastGlfwError(); call before glfwInit so that its failure is explained too.
void captureGlfwErrors();
// The last message GLFW reported ("" before any).
const std::string& lastGlfwError();

}  // namespace bricklight::viewer
