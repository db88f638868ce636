// Per-pass GPU milliseconds from the device's timed markers, and a history of frame times for the graph.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "bricklight/rhi.h"

namespace bricklight::viewer {

class FrameStats {
public:
    static constexpr size_t kHistory = 240;
    struct Pass {
        std::string label;  // nested markers joined with '/'
        float milliseconds = 0.0f;  // smoothed over frames
        uint64_t lastFrame = 0;     // the frame that last reported it
    };
    // Takes the timings the GPU has finished (IDevice::takeTimings) and the CPU frame time.
    void update(rhi::IDevice& device, float cpuFrameMilliseconds);
    const std::vector<Pass>& passes() const { return passes_; }
    const std::vector<float>& cpuFrameHistory() const { return cpu_; }  // oldest first
    const std::vector<float>& gpuFrameHistory() const { return gpu_; }  // the outermost markers' sum
    float averageCpuMilliseconds() const;

private:
    std::vector<Pass> passes_;
    std::vector<float> cpu_, gpu_;
    uint64_t frame_ = 0;
};

}  // namespace bricklight::viewer
