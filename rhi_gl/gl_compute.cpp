// dispatch / dispatchIndirect: validate the record, issue the barrier its consumers need, bind, dispatch,
// record its incoherent writes, and leave program 0 and no image unit bound.
#include "gl_device.h"

namespace bricklight::gl::detail {

using namespace rhi;

bool Device::prepareDispatch(const Call& call, const DispatchState& state, ShaderRecord** shaderOut, BindingPlan* plan) {
    ShaderRecord* s = shader(state.shader, call, "shader");
    if (!s) return false;
    if (s->blob->stage != ShaderStage::Compute) return fail(call, detail::describe(*s) + " is not a compute shader");
    Declared declared;
    if (!declare(call, *s, &declared) || !resolveBindings(call, state.bindings, declared, state.flags, plan)) return false;
    *shaderOut = s;
    return true;
}

bool Device::dispatch(const DispatchState& state, uint32_t x, uint32_t y, uint32_t z) {
    makeCurrent();
    Call call{"dispatch", state.label};
    ShaderRecord* s = nullptr;
    BindingPlan plan;
    if (!prepareDispatch(call, state, &s, &plan)) return false;
    const uint32_t groups[3] = {x, y, z};
    for (int i = 0; i < 3; ++i)
        if (groups[i] > caps_.limits.maxComputeGroupCount[i])
            return fail(call, "group count " + std::to_string(groups[i]) + " in dimension " + std::to_string(i) +
                                  " exceeds maxComputeGroupCount " + std::to_string(caps_.limits.maxComputeGroupCount[i]));
    if (!x || !y || !z) return true;  // an empty dispatch does nothing (as in Vulkan)
    barriers_.issue(gl, plan.barriers);
    pushLabel(state.label);
    gl.UseProgram(s->program);
    applyBindings(plan);
    gl.DispatchCompute(x, y, z);
    finishBindings(plan);
    gl.UseProgram(0);
    popLabel(state.label);
    return true;
}

bool Device::dispatchIndirect(const DispatchState& state, BufferHandle argsHandle, uint64_t offset) {
    makeCurrent();
    Call call{"dispatchIndirect", state.label};
    ShaderRecord* s = nullptr;
    BindingPlan plan;
    if (!prepareDispatch(call, state, &s, &plan)) return false;
    BufferRecord* args = buffer(argsHandle, call, "args");
    if (!args) return false;
    if (!(args->desc.usage & BufferUsage::IndirectArgs))
        return fail(call, "args: " + detail::describe(*args) + " was not created with BufferUsage::IndirectArgs");
    if (offset % 4) return fail(call, "offset " + std::to_string(offset) + " is not a multiple of 4");
    if (offset > args->desc.size || args->desc.size - offset < sizeof(DispatchIndirectArgs))
        return fail(call, "args: 12 bytes at offset " + std::to_string(offset) + " exceed the " +
                              std::to_string(args->desc.size) + " bytes of " + detail::describe(*args));
    barriers_.require(&plan.barriers, args->lastShaderWrite, GL_COMMAND_BARRIER_BIT);
    barriers_.issue(gl, plan.barriers);
    pushLabel(state.label);
    gl.UseProgram(s->program);
    applyBindings(plan);
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, args->name);
    gl.DispatchComputeIndirect(GLintptr(offset));
    gl.BindBuffer(GL_DISPATCH_INDIRECT_BUFFER, 0);
    finishBindings(plan);
    gl.UseProgram(0);
    popLabel(state.label);
    return true;
}

}  // namespace bricklight::gl::detail
