#include "glfw_errors.h"

#include <GLFW/glfw3.h>

namespace bricklight::viewer {

namespace {
std::string& message() {
    static std::string text;
    return text;
}
void onGlfwError(int, const char* description) { message() = description ? description : ""; }
}  // namespace

void captureGlfwErrors() { glfwSetErrorCallback(onGlfwError); }

const std::string& lastGlfwError() { return message(); }

}  // namespace bricklight::viewer
