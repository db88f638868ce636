// Shaders for replaying recordings in programs that embed none (the replay fuzzer links only bricklight_rhi):
// stand-ins with reflection and no code, registered under "fuzz/..." names, so that fuzzed dispatches and
// draws get past createShader and reach the validation wrapper's record checks. Only the null device can
// run them. The seeds (seeds/replay_fuzzer/) and the replay regression tests use the same names.
#pragma once

#include "bricklight/rhi.h"

namespace bricklight::fuzz {

inline void registerReplayFuzzShaders() {
    using namespace rhi;
    static const uint32_t kNoSpirv[1] = {0x07230203};  // the SPIR-V magic number and nothing else
    static const char kNoGlsl[] = "// no code: a stand-in for the null device\n";
    // One binding of every class (like rhi_tests/validation_probe.comp).
    static const ReflectedBinding kProbeBindings[] = {
        {"Params", uint8_t(BindingClass::Constants), 0, ResourceDimension::Buffer, ResourceScalar::None, 0, false, false, false, 16, 0},
        {"source", uint8_t(BindingClass::Texture), 0, ResourceDimension::Texture2D, ResourceScalar::Float, 0, true, false, false, 0, 0},
        {"Weights", uint8_t(BindingClass::ReadBuffer), 0, ResourceDimension::Buffer, ResourceScalar::None, 0, true, false, false, 0, 4},
        {"Counters", uint8_t(BindingClass::StorageBuffer), 0, ResourceDimension::Buffer, ResourceScalar::None, 0, false, false, false, 0, 4},
        {"target", uint8_t(BindingClass::StorageImage), 0, ResourceDimension::Texture2D, ResourceScalar::Float,
         uint8_t(Format::RGBA16_FLOAT), false, false, false, 0, 0},
    };
    static const ReflectedVertexInput kTriangleInputs[] = {
        {"position", 0, 3, ResourceScalar::Float},
        {"color", 1, 4, ResourceScalar::Float},
    };
    static const ShaderBlob kBlobs[] = {
        {"fuzz/probe.comp", ShaderStage::Compute, kNoGlsl, kNoSpirv, 1,
         {{8, 8, 1}, kProbeBindings, 5, nullptr, 0, 0, {1, 1, 1, 1, 1}}},
        {"fuzz/triangle.vert", ShaderStage::Vertex, kNoGlsl, kNoSpirv, 1,
         {{0, 0, 0}, nullptr, 0, kTriangleInputs, 2, 0, {0, 0, 0, 0, 0}}},
        {"fuzz/triangle.frag", ShaderStage::Fragment, kNoGlsl, kNoSpirv, 1,
         {{0, 0, 0}, nullptr, 0, nullptr, 0, 1, {0, 0, 0, 0, 0}}},
        {"fuzz/points.geom", ShaderStage::Geometry, kNoGlsl, kNoSpirv, 1,
         {{0, 0, 0}, nullptr, 0, nullptr, 0, 0, {0, 0, 0, 0, 0}}},
    };
    static const rhi::detail::ShaderRegistration registration(kBlobs, sizeof(kBlobs) / sizeof(kBlobs[0]));
}

}  // namespace bricklight::fuzz
