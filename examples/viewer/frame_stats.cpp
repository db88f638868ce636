#include "frame_stats.h"

#include <algorithm>
#include <map>

namespace bricklight::viewer {

namespace {
void push(std::vector<float>& history, float value) {
    if (history.size() == FrameStats::kHistory) history.erase(history.begin());
    history.push_back(value);
}
}  // namespace

void FrameStats::update(rhi::IDevice& device, float cpuFrameMilliseconds) {
    ++frame_;
    push(cpu_, cpuFrameMilliseconds);
    // Timings arrive a few frames late and possibly several frames at once: one GPU total per frame.
    std::map<uint64_t, float> gpuTotals;
    for (const rhi::MarkerTiming& t : device.takeTimings()) {
        auto it = std::find_if(passes_.begin(), passes_.end(), [&](const Pass& p) { return p.label == t.label; });
        if (it == passes_.end()) {
            passes_.push_back({t.label, float(t.milliseconds), frame_});
        } else {
            it->milliseconds = 0.9f * it->milliseconds + 0.1f * float(t.milliseconds);  // steady enough to read
            it->lastFrame = frame_;
        }
        if (t.label.find('/') == std::string::npos) gpuTotals[t.frame] += float(t.milliseconds);
    }
    for (const auto& [frame, total] : gpuTotals) push(gpu_, total);
    // Passes that stopped reporting (GI turned off) leave the table after a second or so.
    passes_.erase(std::remove_if(passes_.begin(), passes_.end(), [&](const Pass& p) { return frame_ - p.lastFrame > 120; }),
                  passes_.end());
}

float FrameStats::averageCpuMilliseconds() const {
    if (cpu_.empty()) return 0.0f;
    float sum = 0.0f;
    for (float v : cpu_) sum += v;
    return sum / float(cpu_.size());
}

}  // namespace bricklight::viewer
