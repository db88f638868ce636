// What the GL backend needs of the platform: headless contexts (OSMesa and EGL on Unix, in
// gl_headless_unix.cpp; WGL on Windows, in gl_headless_wgl.cpp) and the host's memory size. Each platform's
// file defines every function: an API the platform lacks returns null with a message that says so.
#pragma once

#include <cstdint>
#include <memory>
#include <string>

#include "bricklight/rhi_gl.h"

namespace bricklight::gl {

std::unique_ptr<HeadlessContext> createOsmesaContext(std::string* error);
std::unique_ptr<HeadlessContext> createEglContext(std::string* error);
std::unique_ptr<HeadlessContext> createWglContext(std::string* error);

// Physical memory of the host (0 when unknown): the bound on one resource where the GL driver tells none.
uint64_t hostMemoryBytes();

}  // namespace bricklight::gl
