// The kit's machinery: case registry, running a case on a backend under the validation wrapper, and
// comparing two backends' outputs.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

#include "bricklight/conformance.h"
#include "bricklight/rhi_validation.h"

namespace bricklight::conformance {

namespace {
std::vector<Case>& registry() {
    static std::vector<Case> all;
    return all;
}

}  // namespace

detail::CaseRegistration::CaseRegistration(const char* name, const char* covers, void (*run)(CaseContext&)) {
    registry().push_back(Case{name, covers, run});
}

const std::vector<Case>& cases() {
    static const std::vector<Case> sorted = [] {
        std::vector<Case> c = registry();
        std::sort(c.begin(), c.end(), [](const Case& a, const Case& b) { return std::strcmp(a.name, b.name) < 0; });
        return c;
    }();
    return sorted;
}

bool CaseContext::check(bool condition, const std::string& what) {
    if (!condition) failures.push_back(what);
    return condition;
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

int64_t CaseContext::barriers() const {
    if (!backend.barrierCount) return -1;
    return int64_t(backend.barrierCount(device) - barrierBase);
}

CaseResult runCase(const Case& c, const Backend& backend) {
    CaseResult result;
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
        // Barriers are counted on the inner device: the wrapper issues none of its own.
        Backend view = backend;
        rhi::IDevice* innerPtr = inner.get();
        if (backend.barrierCount)
            view.barrierCount = [&backend, innerPtr](rhi::IDevice&) { return backend.barrierCount(*innerPtr); };
        CaseContext run(*device, view);
        run.barrierBase = backend.barrierCount ? backend.barrierCount(*inner) : 0;
        c.run(run);
        device->waitIdle();
        result.failures = std::move(run.failures);
        result.outputs = std::move(run.outputs);
    }
    inner.reset();
    for (auto& m : reported) result.failures.push_back("device reported " + m);
    result.passed = result.failures.empty();
    return result;
}

std::vector<std::string> compareOutputs(const CaseResult& a, const CaseResult& b) {
    std::vector<std::string> diffs;
    if (a.outputs.size() != b.outputs.size()) {
        diffs.push_back("different number of outputs: " + std::to_string(a.outputs.size()) + " vs " +
                        std::to_string(b.outputs.size()));
        return diffs;
    }
    for (size_t i = 0; i < a.outputs.size(); ++i) {
        const Output& x = a.outputs[i];
        const Output& y = b.outputs[i];
        if (x.name != y.name || x.bytes.size() != y.bytes.size()) {
            diffs.push_back("output " + x.name + ": size or name differs");
            continue;
        }
        size_t bad = 0, first = SIZE_MAX;
        double worst = 0.0;
        switch (x.tolerance.kind) {
            case Tolerance::Kind::Exact:
                for (size_t k = 0; k < x.bytes.size(); ++k)
                    if (x.bytes[k] != y.bytes[k]) ++bad, first = std::min(first, k);
                break;
            case Tolerance::Kind::Unorm8:
                for (size_t k = 0; k < x.bytes.size(); ++k) {
                    double d = std::abs(int(x.bytes[k]) - int(y.bytes[k]));
                    worst = std::max(worst, d);
                    if (d > x.tolerance.absolute) ++bad, first = std::min(first, k);
                }
                break;
            case Tolerance::Kind::Float32:
                for (size_t k = 0; k + 4 <= x.bytes.size(); k += 4) {
                    float fa, fb;
                    std::memcpy(&fa, &x.bytes[k], 4);
                    std::memcpy(&fb, &y.bytes[k], 4);
                    double d = std::isnan(fa) != std::isnan(fb) ? INFINITY : std::abs(double(fa) - fb);
                    if (std::isnan(fa) && std::isnan(fb)) d = 0;
                    worst = std::max(worst, d);
                    if (d > x.tolerance.absolute) ++bad, first = std::min(first, k);
                }
                break;
        }
        if (bad) {
            std::ostringstream m;
            m << "output " << x.name << ": " << bad << " element(s) differ beyond tolerance " << x.tolerance.absolute
              << " (first at byte " << first << ", largest difference " << worst << ")";
            diffs.push_back(m.str());
        }
    }
    return diffs;
}

}  // namespace bricklight::conformance
