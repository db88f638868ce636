// What the image-sized techniques share (shadows, reflections, the depth pyramid; internal to core): the size limit,
// the finiteness checks of their descriptions (core/common/finite_checks.h), and the creation of their passes' shaders.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <string>
#include <utility>

#include "bricklight/rhi.h"
#include "core_shaders.h"
#include "finite_checks.h"

namespace bricklight::detail {

constexpr uint32_t kMaxSize = 16384;  // pixels per side

// "" for a size of 1..kMaxSize on each side, else what is wrong with it.
inline std::string sizeProblem(uint32_t width, uint32_t height) {
    if (width != 0 && height != 0 && width <= kMaxSize && height <= kMaxSize) return {};
    return "size " + std::to_string(width) + "x" + std::to_string(height) + " is outside 1.." + std::to_string(kMaxSize) + " on each side";
}

// Each named pass's shader, after the technique's anchor `linkShaders` (core/common/core_shaders.h) has registered
// its library's passes; null where the device refuses one.
inline void createShaders(rhi::IDevice& device, void (*linkShaders)(),
                          std::initializer_list<std::pair<const char*, rhi::ShaderHandle*>> shaders) {
    linkShaders();
    for (auto [name, shader] : shaders) *shader = bricklight::shaders::createCoreShader(device, name);
}

}  // namespace bricklight::detail
