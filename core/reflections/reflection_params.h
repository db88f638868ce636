// The reflection classifier's parameter block: shaders/reflections/reflection_params.glsl's ReflectionParams (std430),
// shared by reflection_classifier.cpp and reflection_trace.cpp. Sections: the classification's (up to `trace`),
// the trace's (`trace`, `trace2`), the debug view's (`debug`), each written only when it changes.
#pragma once

#include <cstddef>

#include <glm/glm.hpp>

#include "bricklight/reflections/classifier.h"

namespace bricklight::reflections {

struct ReflectionParams {
    glm::mat4 inverseViewProjection, viewProjection, previousViewProjection, inverseProjection;
    glm::vec4 normalScale, normalBias, hybrid;
    glm::uvec4 size, options, options2, frame;
    glm::uvec4 trace;
    glm::vec4 trace2;
    glm::uvec4 debug;
};
static_assert(sizeof(ReflectionParams) == 64 * 4 + 16 * 10);
static_assert(sizeof(ReflectionParams) <= kReflectionParamsBytes);

}  // namespace bricklight::reflections
