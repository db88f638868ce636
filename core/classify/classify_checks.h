// What the classifiers, the denoisers and the depth pyramid share (internal to core/classify): the size limit,
// the finiteness checks of their descriptions (core/finite_checks.h), and the creation of their passes' shaders.
#pragma once

#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>

#include <glm/glm.hpp>

#include "bricklight/rhi.h"
#include "../core_shaders.h"
#include "../finite_checks.h"

namespace bricklight::classify::detail {

constexpr uint32_t kMaxSize = 16384;  // pixels per side

using bricklight::detail::finite;  // core/finite_checks.h

// "" for a size of 1..kMaxSize on each side, else what is wrong with it.
inline std::string sizeProblem(uint32_t width, uint32_t height) {
    if (width != 0 && height != 0 && width <= kMaxSize && height <= kMaxSize) return {};
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." + std::to_string(kMaxSize) + " on each side";
}

// Each named pass's shader (core/CMakeLists.txt embeds them; null where the device refuses one).
inline void createShaders(rhi::IDevice& device, std::initializer_list<std::pair<const char*, rhi::ShaderHandle*>> shaders) {
    bricklight::shaders::link_bricklight_core();
    for (auto [name, shader] : shaders) {
        rhi::ShaderDesc sd;
        sd.blob = rhi::findShader(name);
        *shader = sd.blob ? device.createShader(sd) : rhi::ShaderHandle{};
    }
}

}  // namespace bricklight::classify::detail
