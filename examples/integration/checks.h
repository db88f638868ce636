// After the last frame: read the images back (blocking; a tool's job, never a frame's), print figures,
// decide pass/fail, and write the lit image.
#pragma once

#include <string>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"
#include "passes.h"
#include "scene.h"

namespace integration {

struct CheckInputs {
    const Room* room = nullptr;
    glm::mat4 viewProjection{1.0f};
    uint32_t width = 0, height = 0;
    float shadowRayOffset = 0.0f;  // the composite's, so the exact reference rays start where the GPU's did
};

// Prints "check <what> ok|FAILED"; returns ok.
bool reportCheck(bool ok, const std::string& what);

// Prints one line per figure and per check; true when every check passes.
bool checkFrame(bricklight::rhi::IDevice& device, const FrameImages& images, const CheckInputs& in);

// Binary PPM (8 bit, tone-mapped x / (1 + x), gamma 2.2) or, for a name ending in .pfm, linear floats.
bool writeLitImage(bricklight::rhi::IDevice& device, const FrameImages& images, uint32_t width, uint32_t height,
                   const std::string& path);

}  // namespace integration
