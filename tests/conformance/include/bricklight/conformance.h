// The RHI conformance kit: test cases that take any IDevice, so an integrator runs the same suite against
// their own RHI that our Vulkan and GL backends pass. Each case checks its results against expected values
// and also registers its outputs so that two backends can be compared with each other.
//
//   bricklight::conformance::Backend mine{"my-engine", [] { return makeMyDevice(); }};
//   auto result = bricklight::conformance::runCase(bricklight::conformance::cases()[0], mine);
//
// or, with Catch2, registerCatchTests({mine}) before running the session (see tests/conformance/main.cpp).
#pragma once

#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::conformance {

struct Backend {
    std::string name;
    std::function<std::unique_ptr<rhi::IDevice>()> createDevice;
    // Optional: how many barriers the device has issued so far (lets hazard cases check that a
    // dependency got a barrier and that read-after-read got none). Leave empty if the RHI cannot tell.
    std::function<uint64_t(rhi::IDevice&)> barrierCount;
};

// How two backends' outputs are compared.
struct Tolerance {
    enum class Kind { Exact, Float32, Unorm8 } kind = Kind::Exact;
    double absolute = 0.0;  // Float32: |a-b| per float; Unorm8: per byte
};

struct Output {
    std::string name;
    std::vector<uint8_t> bytes;
    Tolerance tolerance;
};

class CaseContext {
public:
    CaseContext(rhi::IDevice& device, const Backend& backend) : device(device), backend(backend) {}

    rhi::IDevice& device;
    const Backend& backend;

    // Records a failure; the case goes on so that every failure is reported.
    bool check(bool condition, const std::string& what);
    void fail(const std::string& what) { failures.push_back(what); }
    void output(const std::string& name, std::vector<uint8_t> bytes, Tolerance tolerance = {});

    // Creates a shader from the embedded blob `name`; fails the case if it does not exist.
    rhi::ShaderHandle shader(const char* name);
    rhi::BufferHandle buffer(uint64_t size, uint32_t usage, const void* data = nullptr, const char* name = "buffer");
    rhi::TextureHandle texture(const rhi::TextureDesc& desc, const void* data = nullptr);
    rhi::SamplerHandle sampler(const rhi::SamplerDesc& desc);

    template <typename T>
    std::vector<T> read(rhi::BufferHandle buffer, size_t count, uint64_t offset = 0) {
        std::vector<T> out(count);
        if (!device.readBuffer(buffer, offset, count * sizeof(T), out.data())) fail("readBuffer failed");
        return out;
    }
    std::vector<uint8_t> readTexture(rhi::TextureHandle texture, rhi::TextureSubresource sub = {});

    // Barriers issued since the case began, or -1 when the backend does not report them.
    int64_t barriers() const;

    std::vector<std::string> failures;
    std::vector<Output> outputs;
    uint64_t barrierBase = 0;
};

struct Case {
    const char* name;
    const char* covers;  // the record fields / features this case exercises
    void (*run)(CaseContext&);
};

// Every case of the kit, in a stable order.
const std::vector<Case>& cases();

struct CaseResult {
    bool passed = false;
    std::vector<std::string> failures;      // case checks and every error/warning the device reported
    std::vector<Output> outputs;
};

// Creates a device (under the validation wrapper), runs the case, destroys the device. Any error the
// device or the wrapper reports during the case is a failure.
CaseResult runCase(const Case& c, const Backend& backend);

// Compares the outputs of two runs of one case; returns the differences (empty = equal within tolerance).
std::vector<std::string> compareOutputs(const CaseResult& a, const CaseResult& b);

// Registers one Catch2 test per (backend, case) tagged [conformance][<backend name>], and one
// "cross" test per case comparing the first two backends, tagged [conformance][cross].
void registerCatchTests(const std::vector<Backend>& backends);

namespace detail {
struct CaseRegistration {
    CaseRegistration(const char* name, const char* covers, void (*run)(CaseContext&));
};
}  // namespace detail

}  // namespace bricklight::conformance

// Defines and registers a case: BL_CONFORMANCE_CASE(storage_buffer_fill, "storageBuffers, constants") { ... }
#define BL_CONFORMANCE_CASE(ident, covers)                                                              \
    static void ident(::bricklight::conformance::CaseContext& ctx);                                     \
    static ::bricklight::conformance::detail::CaseRegistration ident##_registration(#ident, covers, ident); \
    static void ident([[maybe_unused]] ::bricklight::conformance::CaseContext& ctx)
