// What the replay tests share: a recorded session that uses every call the recorder writes (each call
// valid), helpers that replay text and report how it went, and a device that keeps buffer contents.
#pragma once

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "bricklight/rhi_validation.h"
#include "forwarding_test_device.h"

namespace bricklight::testing {

using nlohmann::json;

// Seconds within which every replay of a test must finish (generous: sanitizer builds are slow).
constexpr double kReplaySecondsBound = 5.0;

// The calls of a small session, each one valid: textures (with initial data), buffers, a sampler, compute
// and graphics shaders, every transfer, every kind of dispatch and draw, markers, timing, frame calls,
// destruction. Made on `device`.
void runSession(rhi::IDevice& device);
// That session recorded on the null device under the validation wrapper: one JSON object per line.
std::vector<json> sessionLines();
std::string joinLines(const std::vector<json>& lines);
// Index of the first line whose "call" is `call`; fails the test if there is none.
size_t lineOf(const std::vector<json>& lines, const std::string& call);

struct ReplayResult {
    bool ok = false;
    bool threw = false;
    rhi::ReplayStats stats;
    std::string error;
    std::vector<std::string> deviceErrors;
    double seconds = 0;
};
// Replays `text` on `device` (whose error callback it takes over), timing it and catching what escapes.
ReplayResult replayOn(rhi::IDevice& device, const std::string& text, const rhi::ReplayOptions& options = {});
// On a fresh null device, under the validation wrapper unless `validate` is false.
ReplayResult replayText(const std::string& text, bool validate = true, const rhi::ReplayOptions& options = {});

// The null device with buffer contents kept, so that a test can read back what a replay wrote. Buffers of
// more than 1 MiB are refused (a test device, not a store for hostile sizes).
class BufferMemoryDevice : public ForwardingTestDevice {
public:
    explicit BufferMemoryDevice(rhi::IDevice& inner) : ForwardingTestDevice(inner) {}
    rhi::BufferHandle createBuffer(const rhi::BufferDesc& desc, const void* data) override;
    void destroy(rhi::BufferHandle h) override;
    using ForwardingTestDevice::destroy;
    bool writeBuffer(rhi::BufferHandle b, uint64_t offset, const void* data, uint64_t size) override;
    bool copyBuffer(rhi::BufferHandle dst, uint64_t dstOffset, rhi::BufferHandle src, uint64_t srcOffset,
                    uint64_t size) override;
    bool clearBuffer(rhi::BufferHandle b, rhi::BufferRange range, uint32_t value) override;
    bool readBuffer(rhi::BufferHandle b, uint64_t offset, uint64_t size, void* out) override;
    const std::vector<uint8_t>* contents(rhi::BufferHandle b) const;

private:
    std::vector<uint8_t>* find(rhi::BufferHandle b, uint64_t offset, uint64_t size);
    std::map<uint32_t, std::vector<uint8_t>> buffers_;
};

}  // namespace bricklight::testing
