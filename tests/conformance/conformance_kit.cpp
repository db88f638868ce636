// The kit's machinery: what a case can do (CaseContext) and running a case on a backend under the
// validation wrapper.
#include <algorithm>

#include "bricklight/conformance.h"
#include "bricklight/rhi_validation.h"

namespace bricklight::shaders {
void link_bricklight_rhi_test_shaders();  // the kit's shaders (shaders/CMakeLists.txt)
}

namespace bricklight::conformance {

bool CaseContext::check(bool condition, const std::string& what) {
    if (!condition) failures.push_back(what);
    return condition;
}

void CaseContext::note(const std::string& what) {
    if (std::find(notes.begin(), notes.end(), what) == notes.end()) notes.push_back(what);
}

void CaseContext::output(const std::string& name, std::vector<uint8_t> bytes, Tolerance tolerance) {
    outputs.push_back(Output{name, std::move(bytes), tolerance});
}

rhi::ShaderHandle CaseContext::shader(const char* name) {
    const rhi::ShaderBlob* blob = rhi::findShader(name);
    if (!blob) {
        fail(std::string("shader '") + name + "' is not embedded");
        return {};
    }
    rhi::ShaderHandle h = device.createShader({blob, ""});
    check(bool(h), std::string("createShader '") + name + "' failed");
    return h;
}

rhi::BufferHandle CaseContext::buffer(uint64_t size, uint32_t usage, const void* data, const char* name) {
    rhi::BufferDesc d;
    d.size = size;
    d.usage = usage;
    d.debugName = name;
    rhi::BufferHandle h = device.createBuffer(d, data);
    check(bool(h), std::string("createBuffer '") + name + "' failed");
    return h;
}

rhi::TextureHandle CaseContext::texture(const rhi::TextureDesc& desc, const void* data) {
    rhi::TextureHandle h = device.createTexture(desc, data);
    check(bool(h), "createTexture '" + desc.debugName + "' failed");
    return h;
}

rhi::SamplerHandle CaseContext::sampler(const rhi::SamplerDesc& desc) {
    rhi::SamplerHandle h = device.createSampler(desc);
    check(bool(h), "createSampler '" + desc.debugName + "' failed");
    return h;
}

std::vector<uint8_t> CaseContext::readTexture(rhi::TextureHandle texture, rhi::TextureSubresource sub) {
    const rhi::TextureDesc* d = device.describe(texture);
    if (!d) {
        fail("readTexture: texture not live");
        return {};
    }
    std::vector<uint8_t> out(rhi::subresourceBytes(*d, sub));
    if (!device.readTexture(texture, sub, out.data())) fail("readTexture '" + d->debugName + "' failed");
    return out;
}

std::optional<uint64_t> CaseContext::barriers() {
    std::optional<uint64_t> count = barrierCounter ? barrierCounter() : std::nullopt;
    if (!count) note("barrier count unsupported by this backend: check skipped");
    return count;
}

CaseResult runCase(const Case& c, const Backend& backend) {
    shaders::link_bricklight_rhi_test_shaders();
    CaseResult result;
    if (!backend.createDevice) {
        result.failures.push_back("backend '" + backend.name + "' has no createDevice function");
        return result;
    }
    std::unique_ptr<rhi::IDevice> inner = backend.createDevice();
    if (!inner) {
        result.failures.push_back("backend '" + backend.name + "' could not create a device");
        return result;
    }
    std::vector<std::string> reported;
    {
        std::unique_ptr<rhi::IDevice> device = rhi::createValidationDevice(*inner);
        device->setErrorCallback([&](rhi::Severity s, const std::string& m) {
            if (s != rhi::Severity::Info) reported.push_back((s == rhi::Severity::Error ? "error: " : "warning: ") + m);
        });
        CaseContext run(*device, backend);
        // Barriers are counted on the backend's own device: the wrapper issues none of its own.
        rhi::IDevice* created = inner.get();
        if (backend.barrierCount) run.barrierCounter = [&backend, created] { return backend.barrierCount(*created); };
        c.run(run);
        device->waitIdle();
        result.failures = std::move(run.failures);
        result.notes = std::move(run.notes);
        result.outputs = std::move(run.outputs);
    }
    inner.reset();
    for (auto& m : reported) result.failures.push_back("device reported " + m);
    result.passed = result.failures.empty();
    return result;
}

}  // namespace bricklight::conformance
