// GLFW gives the reason for a failure (no display, no context of the version asked for) only to its error
// callback: both window backends keep it to put into their messages.
#pragma once

#include <string>

namespace bricklight::viewer {

// Routes GLFW's error messages to lastGlfwError(); call before glfwInit so that its failure is explained too.
void captureGlfwErrors();
// The last message GLFW reported ("" before any).
const std::string& lastGlfwError();

}  // namespace bricklight::viewer
