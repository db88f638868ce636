// Hybrid reflections' distance-field rays (GiContext::traceReflectionRays, shaders/gi/reflection_trace.comp): the
// checks of the ray list and output, and the indirect dispatch over the list.
#include "gi_context_impl.h"

namespace bricklight::gi::detail {

bool GiContextImpl::traceReflectionRays(const ReflectionRaysDesc& r) {
    if (!sceneAlive()) return false;
    if (!lastInputs_.depth) return fail(ErrorCode::InvalidState, "traceReflectionRays: no dispatch() yet: the rays need this frame's G-buffer and caches");
    for (rhi::TextureHandle t : {lastInputs_.depth, lastInputs_.normals, lastInputs_.roughness})
        if (!device_.describe(t))
            return fail(ErrorCode::DependencyDestroyed, "traceReflectionRays: the last dispatch()'s depth, normals or roughness texture was destroyed");
    // A buffer: live, with the usage and the bytes [offset, offset + bytes).
    auto buffer = [&](const char* what, rhi::BufferHandle b, uint32_t usage, uint64_t offset, uint64_t bytes) -> bool {
        if (!b) return fail(ErrorCode::MissingInput, std::string("traceReflectionRays: '") + what + "' is missing");
        const rhi::BufferDesc* bd = device_.describe(b);
        if (!bd) return fail(ErrorCode::InvalidHandle, std::string("traceReflectionRays: '") + what + "' is not a live buffer");
        const std::string name = std::string("traceReflectionRays: '") + what + "' (buffer '" + bd->debugName + "')";
        if (!(bd->usage & usage)) return fail(ErrorCode::WrongFormat, name + " lacks the usage it is bound with (read or indirect arguments)");
        if (offset % 4 != 0 || offset > bd->size || bd->size - offset < bytes)
            return fail(ErrorCode::InvalidArgument, name + " is " + std::to_string(bd->size) + " bytes: it does not hold " + std::to_string(bytes) +
                                                        " bytes at offset " + std::to_string(offset) + " (4-byte aligned)");
        return true;
    };
    if (!buffer("rays", r.rays, rhi::BufferUsage::ShaderRead, 0, 4) ||
        !buffer("arguments", r.arguments, rhi::BufferUsage::IndirectArgs, r.argumentsOffset, 12) ||
        !buffer("count", r.count, rhi::BufferUsage::ShaderRead, r.countOffset, 4))
        return false;
    if (!r.output) return fail(ErrorCode::MissingInput, "traceReflectionRays: 'output' is missing");
    const rhi::TextureDesc* td = device_.describe(r.output);
    if (!td) return fail(ErrorCode::InvalidHandle, "traceReflectionRays: 'output' is not a live texture");
    const std::string name = "traceReflectionRays: 'output' (texture '" + td->debugName + "')";
    if (td->dimension != rhi::TextureDimension::Texture2D || td->format != rhi::Format::RGBA16_FLOAT || !(td->usage & rhi::TextureUsage::Storage))
        return fail(ErrorCode::WrongFormat, name + " must be a 2D RGBA16_FLOAT texture with Storage usage, not " + rhi::formatName(td->format));
    if (td->width != desc_.displayWidth || td->height != desc_.displayHeight)
        return fail(ErrorCode::WrongSize, name + " is " + std::to_string(td->width) + "x" + std::to_string(td->height) + "; it must be the display size " +
                                              std::to_string(desc_.displayWidth) + "x" + std::to_string(desc_.displayHeight));
    for (rhi::TextureHandle in : {lastInputs_.depth, lastInputs_.normals, lastInputs_.roughness})
        if (in == r.output) return fail(ErrorCode::Aliasing, name + " is also an input of the last dispatch()");
    if (r.count == r.rays && r.countOffset == 0) return fail(ErrorCode::Aliasing, "traceReflectionRays: the count is the list's first entry");

    reflectionPass_ = {{uint32_t(r.countOffset / 4), r.frameIndex, 0, 0}};
    rhi::DispatchState s;
    s.bindings.constants.push(rhi::constants(2, reflectionPass_));
    texture(s.bindings, 0, lastInputs_.depth, point_);
    texture(s.bindings, 1, lastInputs_.normals, point_);
    texture(s.bindings, 2, lastInputs_.roughness, point_);
    readBuffer(s.bindings, 0, r.rays);
    readBuffer(s.bindings, 1, r.count);
    readBuffer(s.bindings, 3, slotOfBrick_);
    image(s.bindings, 0, r.output, rhi::Access::ReadWrite);
    image(s.bindings, 1, radianceCache_, rhi::Access::Read);
    addTrace(s.bindings);
    addAlphaCache(s.bindings);
    addEnvironment(s.bindings, lastInputs_.environment);
    prepare("reflection rays", shaders_.reflectionTrace, s);
    device_.beginMarker("reflection rays");
    device_.dispatchIndirect(s, r.arguments, r.argumentsOffset);
    device_.endMarker();
    return true;
}

}  // namespace bricklight::gi::detail
