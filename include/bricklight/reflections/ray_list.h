// The reflection ray list: the contract between the reflection classifier, which lists the rays
// (reflections::ReflectionClassifier), and a tracer of the list (gi::GiContext::traceReflectionRays, or the
// application's own). One uint per ray; the list's dispatchIndirect arguments count groups of
// kReflectionRaysPerGroup rays. docs/reflections.md, "Hybrid reflections".
#pragma once

#include <cstdint>

#include <glm/glm.hpp>

namespace bricklight {

constexpr uint32_t kReflectionRaysPerGroup = 64;      // rays a group of the list's tracer (1-D, 64 threads)
constexpr uint32_t kReflectionSkippedEntry = 0xFFFFFFFFu;  // padding in a list: no ray

// A ray's entry: pixel x in bits 0..14, y in 15..28; bits 29, 30, 31 ask the tracer to copy the ray's result to
// the pixel's quad neighbour across x (x ^ 1), across y (y ^ 1) and across both, which are glossy but have no ray
// of their own (samplesPerQuad < 4).
inline uint32_t packReflectionRay(uint32_t x, uint32_t y, uint32_t copyFlags = 0) { return x | (y << 15) | (copyFlags << 29); }
inline glm::uvec2 reflectionRayPixel(uint32_t packed) { return glm::uvec2(packed & 0x7FFFu, (packed >> 15) & 0x3FFFu); }

}  // namespace bricklight
