// The RHI conformance kit: test cases that take any IDevice, so an integrator runs the same suite against
// their own RHI that our Vulkan and GL backends pass. Each case checks its results against expected values
// and also keeps its outputs so that two backends can be compared with each other.
//
//   bricklight::conformance::Backend mine{"my-engine", [] { return makeMyDevice(); }};
//   return bricklight::conformance::runAll({mine});      // every case, one line each; the exit code
//
// Link bricklight::conformance (CMake) or, by hand, libbricklight_conformance.a, then
// libbricklight_rhi_test_shaders.a (the cases' shaders) and libbricklight_rhi.a (docs/rhi.md, "Running the
// conformance kit on your RHI"). Catch2 is not needed; tests/conformance/catch2 registers the cases as
// Catch2 tests for those who want that.
#pragma once

#include <cstdint>
#include <functional>
#include <iosfwd>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::conformance {

struct Backend {
    std::string name;
    // A new device for each case (the kit wraps it in the validation wrapper and destroys it afterwards).
    std::function<std::unique_ptr<rhi::IDevice>()> createDevice;
    // Optional: how many barriers the device has issued so far, called with the device that createDevice
    // returned. It lets the hazard cases check that every dependency got a barrier and that read-after-read
    // got none. Leave it empty, or return std::nullopt, when the RHI cannot tell: the hazard cases then skip
    // those checks and say so in CaseResult::notes.
    std::function<std::optional<uint64_t>(rhi::IDevice&)> barrierCount;
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
    // Records something the reader should know that is not a failure (a check skipped); once per text.
    void note(const std::string& what);
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

    // Barriers the device has issued so far (compare two calls), or empty when the backend cannot tell; then
    // it notes "barrier count unsupported by this backend: check skipped".
    std::optional<uint64_t> barriers();

    std::vector<std::string> failures;
    std::vector<std::string> notes;
    std::vector<Output> outputs;
    // Set by runCase: the backend's barrierCount bound to the device it created (the wrapper has none).
    std::function<std::optional<uint64_t>()> barrierCounter;
};

struct Case {
    const char* name;
    const char* covers;  // the record fields / features this case exercises
    void (*run)(CaseContext&);
};

// Every case of the kit, sorted by name.
const std::vector<Case>& cases();

struct CaseResult {
    bool passed = false;
    std::vector<std::string> failures;  // case checks and every error/warning the device reported
    std::vector<std::string> notes;     // not failures: checks the backend could not support, skipped
    std::vector<Output> outputs;
};

// Creates a device (under the validation wrapper), runs the case, destroys the device. Any error the
// device or the wrapper reports during the case is a failure.
CaseResult runCase(const Case& c, const Backend& backend);

// Compares the outputs of two runs of one case; returns the differences (empty = equal within tolerance).
std::vector<std::string> compareOutputs(const CaseResult& a, const CaseResult& b);

struct RunOptions {
    // Runs only the cases whose name contains one of these strings; every case when empty.
    std::vector<std::string> filters;
    // Where the report goes; null: std::cout.
    std::ostream* out = nullptr;
};

// The plain runner: runs every selected case on every backend, and when there are two or more backends
// compares each case's outputs on the first two. Prints one line per run and comparison ("passed" or
// "failed", the failures and notes indented below it), then a summary. Returns a process exit code: 0 when
// every run passed and every comparison agreed, 1 otherwise (also when the filters select no case or there
// is no backend).
int runAll(const std::vector<Backend>& backends, const RunOptions& options = {});

}  // namespace bricklight::conformance
